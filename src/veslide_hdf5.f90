!> A thin HDF5 file handle in the shape of h5fortran's API, over the HDF5 Fortran library.
!>
!> Datasets are created with their intermediate groups. Fortran arrays are stored as they are:
!> a Fortran (nx, ny) array reads in h5py with shape (ny, nx).
module veslide_hdf5
    use hdf5
    use veslide_kinds, only: dp
    use veslide_error, only: error_t, fatal_error
    implicit none
    private
    public :: h5file_t, hdf5_library_version

    type :: h5file_t
        integer(hid_t) :: fid = -1          !! file id (-1: closed)
        character(len=:), allocatable :: path
    contains
        procedure :: open => h5_open
        procedure :: close => h5_close
        procedure :: is_open => h5_is_open
        procedure :: exists => h5_exists
        generic :: write => write_r0, write_i0, write_r1, write_r2, write_i1, write_text
        procedure, private :: write_r0, write_i0, write_r1, write_r2, write_i1, write_text
        generic :: writeattr => attr_text, attr_r0, attr_i0
        procedure, private :: attr_text, attr_r0, attr_i0
        procedure :: write_table => h5_write_table
        procedure :: append_row => h5_append_row
        procedure :: flush => h5_flush
        procedure :: read_r2 => h5_read_r2
        procedure :: read_r0 => h5_read_r0
        procedure :: shape_of => h5_shape_of
        procedure :: attr_exists => h5_attr_exists
        procedure :: read_attr_r0 => h5_read_attr_r0
        final :: h5_finalize
    end type h5file_t

    logical, save :: lib_open = .false.

contains

    subroutine ensure_lib()
        integer :: ierr
        if (.not. lib_open) then
            call h5open_f(ierr)
            call h5eset_auto_f(0, ierr)   ! errors come back as codes, not printed stacks
            lib_open = .true.
        end if
    end subroutine ensure_lib

    !> "major.minor.release" of the HDF5 library in use
    function hdf5_library_version() result(v)
        character(len=:), allocatable :: v
        integer :: maj, mnr, rel, ierr
        character(len=32) :: buf
        call ensure_lib()
        call h5get_libversion_f(maj, mnr, rel, ierr)
        write (buf, '(i0,".",i0,".",i0)') maj, mnr, rel
        v = trim(buf)
    end function hdf5_library_version

    !> Open `path`: action 'w' creates or truncates, 'r' reads
    subroutine h5_open(self, path, action, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: path, action
        type(error_t), allocatable, intent(out) :: error
        integer :: ierr
        call ensure_lib()
        if (self%is_open()) call self%close()
        self%path = path
        select case (action)
        case ('w')
            call h5fcreate_f(path, H5F_ACC_TRUNC_F, self%fid, ierr)
        case ('r')
            call h5fopen_f(path, H5F_ACC_RDONLY_F, self%fid, ierr)
        case default
            ierr = -1
        end select
        if (ierr /= 0) then
            self%fid = -1
            call fatal_error(error, "veslide:hdf5:open: cannot open '"//path//"' for '"//action//"'")
        end if
    end subroutine h5_open

    logical function h5_is_open(self) result(yes)
        class(h5file_t), intent(in) :: self
        yes = self%fid >= 0
    end function h5_is_open

    subroutine h5_close(self)
        class(h5file_t), intent(inout) :: self
        integer :: ierr
        if (self%fid >= 0) call h5fclose_f(self%fid, ierr)
        self%fid = -1
    end subroutine h5_close

    subroutine h5_finalize(self)
        type(h5file_t), intent(inout) :: self
        call self%close()
    end subroutine h5_finalize

    !> Does the link `name` exist (every intermediate group checked)?
    logical function h5_exists(self, name) result(yes)
        class(h5file_t), intent(in) :: self
        character(len=*), intent(in) :: name
        integer :: ierr, k, j
        logical :: e
        yes = .false.
        if (.not. self%is_open()) return
        ! walk the path so that a missing parent group is not an error
        k = 1
        do
            j = index(name(k + 1:), '/')
            if (j == 0) exit
            k = k + j
            call h5lexists_f(self%fid, name(1:k - 1), e, ierr)
            if (ierr /= 0 .or. .not. e) return
        end do
        call h5lexists_f(self%fid, name, yes, ierr)
        if (ierr /= 0) yes = .false.
    end function h5_exists

    !> Create dataset `name` of type `dtype` and dimensions `dims`; returns its id
    subroutine create_dset(self, name, dtype, dims, did, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        integer(hid_t), intent(in) :: dtype
        integer(hsize_t), intent(in) :: dims(:)
        integer(hid_t), intent(out) :: did
        type(error_t), allocatable, intent(out) :: error
        integer(hid_t) :: sid, lcpl
        integer :: ierr
        if (.not. self%is_open()) then
            call fatal_error(error, "veslide:hdf5:write: file not open for "//name); return
        end if
        if (size(dims) == 0) then
            call h5screate_f(H5S_SCALAR_F, sid, ierr)
        else
            call h5screate_simple_f(size(dims), dims, sid, ierr)
        end if
        call h5pcreate_f(H5P_LINK_CREATE_F, lcpl, ierr)
        call h5pset_create_inter_group_f(lcpl, 1, ierr)
        call h5dcreate_f(self%fid, name, dtype, sid, did, ierr, lcpl_id=lcpl)
        call h5pclose_f(lcpl, ierr)
        call h5sclose_f(sid, ierr)
        if (ierr /= 0 .or. did < 0) then
            call fatal_error(error, "veslide:hdf5:write: cannot create "//name//" in "//self%path)
        end if
    end subroutine create_dset

    subroutine finish(did, ierr, name, path, error)
        integer(hid_t), intent(in) :: did
        integer, intent(in) :: ierr
        character(len=*), intent(in) :: name, path
        type(error_t), allocatable, intent(out) :: error
        integer :: ie
        call h5dclose_f(did, ie)
        if (ierr /= 0) call fatal_error(error, "veslide:hdf5:write: cannot write "//name//" in "//path)
    end subroutine finish

    subroutine write_r0(self, name, value, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        real(dp), intent(in) :: value
        type(error_t), allocatable, intent(out) :: error
        integer(hid_t) :: did
        integer :: ierr
        integer(hsize_t) :: dims(0)
        call create_dset(self, name, H5T_NATIVE_DOUBLE, dims, did, error); if (allocated(error)) return
        call h5dwrite_f(did, H5T_NATIVE_DOUBLE, value, dims, ierr)
        call finish(did, ierr, name, self%path, error)
    end subroutine write_r0

    subroutine write_i0(self, name, value, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        integer, intent(in) :: value
        type(error_t), allocatable, intent(out) :: error
        integer(hid_t) :: did
        integer :: ierr
        integer(hsize_t) :: dims(0)
        call create_dset(self, name, H5T_NATIVE_INTEGER, dims, did, error); if (allocated(error)) return
        call h5dwrite_f(did, H5T_NATIVE_INTEGER, value, dims, ierr)
        call finish(did, ierr, name, self%path, error)
    end subroutine write_i0

    subroutine write_r1(self, name, value, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        real(dp), intent(in) :: value(:)
        type(error_t), allocatable, intent(out) :: error
        integer(hid_t) :: did
        integer :: ierr
        integer(hsize_t) :: dims(1)
        dims = shape(value, hsize_t)
        call create_dset(self, name, H5T_NATIVE_DOUBLE, dims, did, error); if (allocated(error)) return
        call h5dwrite_f(did, H5T_NATIVE_DOUBLE, value, dims, ierr)
        call finish(did, ierr, name, self%path, error)
    end subroutine write_r1

    subroutine write_i1(self, name, value, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        integer, intent(in) :: value(:)
        type(error_t), allocatable, intent(out) :: error
        integer(hid_t) :: did
        integer :: ierr
        integer(hsize_t) :: dims(1)
        dims = shape(value, hsize_t)
        call create_dset(self, name, H5T_NATIVE_INTEGER, dims, did, error); if (allocated(error)) return
        call h5dwrite_f(did, H5T_NATIVE_INTEGER, value, dims, ierr)
        call finish(did, ierr, name, self%path, error)
    end subroutine write_i1

    subroutine write_r2(self, name, value, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        real(dp), intent(in) :: value(:, :)
        type(error_t), allocatable, intent(out) :: error
        integer(hid_t) :: did
        integer :: ierr
        integer(hsize_t) :: dims(2)
        dims = shape(value, hsize_t)
        call create_dset(self, name, H5T_NATIVE_DOUBLE, dims, did, error); if (allocated(error)) return
        call h5dwrite_f(did, H5T_NATIVE_DOUBLE, value, dims, ierr)
        call finish(did, ierr, name, self%path, error)
    end subroutine write_r2

    !> Scalar fixed-length string dataset
    subroutine write_text(self, name, value, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: name, value
        type(error_t), allocatable, intent(out) :: error
        integer(hid_t) :: did, tid
        integer :: ierr
        integer(hsize_t) :: dims(0)
        call string_type(len(value), tid)
        call create_dset(self, name, tid, dims, did, error)
        if (allocated(error)) then
            call h5tclose_f(tid, ierr); return
        end if
        call h5dwrite_f(did, tid, value, dims, ierr)
        call h5tclose_f(tid, ierr)
        call finish(did, ierr, name, self%path, error)
    end subroutine write_text

    subroutine string_type(n, tid)
        integer, intent(in) :: n
        integer(hid_t), intent(out) :: tid
        integer :: ierr
        call h5tcopy_f(H5T_FORTRAN_S1, tid, ierr)
        call h5tset_size_f(tid, int(max(n, 1), size_t), ierr)
        call h5tset_strpad_f(tid, H5T_STR_NULLTERM_F, ierr)
    end subroutine string_type

    !> Open object `obj` ('/' for the root) for an attribute; returns its id
    subroutine open_obj(self, obj, oid, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: obj
        integer(hid_t), intent(out) :: oid
        type(error_t), allocatable, intent(out) :: error
        integer :: ierr
        call h5oopen_f(self%fid, obj, oid, ierr)
        if (ierr /= 0) call fatal_error(error, "veslide:hdf5:writeattr: no object "//obj//" in "//self%path)
    end subroutine open_obj

    subroutine attr_text(self, obj, name, value, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: obj, name, value
        type(error_t), allocatable, intent(out) :: error
        integer(hid_t) :: oid, tid, sid, aid
        integer :: ierr
        integer(hsize_t) :: dims(1) = [1]
        call open_obj(self, obj, oid, error); if (allocated(error)) return
        call string_type(len(value), tid)
        call h5screate_f(H5S_SCALAR_F, sid, ierr)
        call h5acreate_f(oid, name, tid, sid, aid, ierr)
        call h5awrite_f(aid, tid, value, dims, ierr)
        if (ierr /= 0) call fatal_error(error, "veslide:hdf5:writeattr: "//obj//"@"//name//" in "//self%path)
        call h5aclose_f(aid, ierr); call h5sclose_f(sid, ierr); call h5tclose_f(tid, ierr)
        call h5oclose_f(oid, ierr)
    end subroutine attr_text

    subroutine attr_r0(self, obj, name, value, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: obj, name
        real(dp), intent(in) :: value
        type(error_t), allocatable, intent(out) :: error
        integer(hid_t) :: oid, sid, aid
        integer :: ierr
        integer(hsize_t) :: dims(1) = [1]
        call open_obj(self, obj, oid, error); if (allocated(error)) return
        call h5screate_f(H5S_SCALAR_F, sid, ierr)
        call h5acreate_f(oid, name, H5T_NATIVE_DOUBLE, sid, aid, ierr)
        call h5awrite_f(aid, H5T_NATIVE_DOUBLE, value, dims, ierr)
        if (ierr /= 0) call fatal_error(error, "veslide:hdf5:writeattr: "//obj//"@"//name//" in "//self%path)
        call h5aclose_f(aid, ierr); call h5sclose_f(sid, ierr); call h5oclose_f(oid, ierr)
    end subroutine attr_r0

    subroutine attr_i0(self, obj, name, value, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: obj, name
        integer, intent(in) :: value
        type(error_t), allocatable, intent(out) :: error
        integer(hid_t) :: oid, sid, aid
        integer :: ierr
        integer(hsize_t) :: dims(1) = [1]
        call open_obj(self, obj, oid, error); if (allocated(error)) return
        call h5screate_f(H5S_SCALAR_F, sid, ierr)
        call h5acreate_f(oid, name, H5T_NATIVE_INTEGER, sid, aid, ierr)
        call h5awrite_f(aid, H5T_NATIVE_INTEGER, value, dims, ierr)
        if (ierr /= 0) call fatal_error(error, "veslide:hdf5:writeattr: "//obj//"@"//name//" in "//self%path)
        call h5aclose_f(aid, ierr); call h5sclose_f(sid, ierr); call h5oclose_f(oid, ierr)
    end subroutine attr_i0

    !> A table as a 1-D compound dataset of float64 columns (pandas.DataFrame(f[name][()]) reads it
    !> in one call); `data(ncol, nrow)`. An existing dataset of that name is replaced.
    subroutine h5_write_table(self, name, columns, data, error)
        use, intrinsic :: iso_c_binding, only: c_loc
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: name, columns(:)
        real(dp), intent(in), target :: data(:, :)
        type(error_t), allocatable, intent(out) :: error
        integer(hid_t) :: tid, did, sid, lcpl
        integer(hsize_t) :: dims(1)
        integer :: ierr, k
        if (self%exists(name)) call h5ldelete_f(self%fid, name, ierr)
        call h5tcreate_f(H5T_COMPOUND_F, int(8*size(columns), size_t), tid, ierr)
        do k = 1, size(columns)
            call h5tinsert_f(tid, trim(columns(k)), int(8*(k - 1), size_t), H5T_NATIVE_DOUBLE, ierr)
        end do
        dims = [int(size(data, 2), hsize_t)]
        call h5screate_simple_f(1, dims, sid, ierr)
        call h5pcreate_f(H5P_LINK_CREATE_F, lcpl, ierr)
        call h5pset_create_inter_group_f(lcpl, 1, ierr)
        call h5dcreate_f(self%fid, name, tid, sid, did, ierr, lcpl_id=lcpl)
        if (ierr == 0 .and. size(data) > 0) call h5dwrite_f(did, tid, c_loc(data), ierr)
        if (ierr /= 0) call fatal_error(error, "veslide:hdf5:write_table: cannot write "//name//" in "//self%path)
        call h5dclose_f(did, k); call h5pclose_f(lcpl, k); call h5sclose_f(sid, k); call h5tclose_f(tid, k)
    end subroutine h5_write_table

    !> Append one row to a table of float64 columns (a 1-D compound dataset, extendible, created
    !> on the first row); each row costs its own size, so a long study does not rewrite its table
    subroutine h5_append_row(self, name, columns, row, error)
        use, intrinsic :: iso_c_binding, only: c_loc
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: name, columns(:)
        real(dp), intent(in), target :: row(:)
        type(error_t), allocatable, intent(out) :: error
        integer(hid_t) :: tid, did, sid, msid, lcpl, dcpl
        integer(hsize_t) :: dims(1), maxdims(1), start(1), cnt(1)
        integer :: ierr, k, ie
        call h5tcreate_f(H5T_COMPOUND_F, int(8*size(columns), size_t), tid, ierr)
        do k = 1, size(columns)
            call h5tinsert_f(tid, trim(columns(k)), int(8*(k - 1), size_t), H5T_NATIVE_DOUBLE, ierr)
        end do
        if (.not. self%exists(name)) then
            dims = [0_hsize_t]; maxdims = [H5S_UNLIMITED_F]
            call h5screate_simple_f(1, dims, sid, ierr, maxdims)
            call h5pcreate_f(H5P_DATASET_CREATE_F, dcpl, ierr)
            call h5pset_chunk_f(dcpl, 1, [64_hsize_t], ierr)
            call h5pcreate_f(H5P_LINK_CREATE_F, lcpl, ierr)
            call h5pset_create_inter_group_f(lcpl, 1, ierr)
            call h5dcreate_f(self%fid, name, tid, sid, did, ierr, dcpl_id=dcpl, lcpl_id=lcpl)
            call h5pclose_f(dcpl, ie); call h5pclose_f(lcpl, ie); call h5sclose_f(sid, ie)
        else
            call h5dopen_f(self%fid, name, did, ierr)
        end if
        if (ierr /= 0) then
            call h5tclose_f(tid, ie)
            call fatal_error(error, "veslide:hdf5:append_row: cannot open "//name//" in "//self%path); return
        end if
        call h5dget_space_f(did, sid, ierr)
        call h5sget_simple_extent_dims_f(sid, dims, maxdims, ierr)
        call h5sclose_f(sid, ie)
        start = dims; cnt = [1_hsize_t]
        dims = dims + 1
        call h5dset_extent_f(did, dims, ierr)
        call h5dget_space_f(did, sid, ierr)
        call h5sselect_hyperslab_f(sid, H5S_SELECT_SET_F, start, cnt, ierr)
        call h5screate_simple_f(1, cnt, msid, ierr)
        call h5dwrite_f(did, tid, c_loc(row), ierr, mem_space_id=msid, file_space_id=sid)
        if (ierr /= 0) call fatal_error(error, "veslide:hdf5:append_row: cannot write a row of "//name)
        call h5sclose_f(msid, ie); call h5sclose_f(sid, ie); call h5dclose_f(did, ie); call h5tclose_f(tid, ie)
    end subroutine h5_append_row

    !> Push what was written to disk (a reader of an unfinished sweep sees every finished case)
    subroutine h5_flush(self)
        class(h5file_t), intent(inout) :: self
        integer :: ierr
        if (self%is_open()) call h5fflush_f(self%fid, H5F_SCOPE_GLOBAL_F, ierr)
    end subroutine h5_flush

    !> Shape of dataset `name` (rank 0..7); `rank` = -1 when absent
    subroutine h5_shape_of(self, name, dims, rank, is_double)
        class(h5file_t), intent(in) :: self
        character(len=*), intent(in) :: name
        integer(hsize_t), intent(out) :: dims(7)
        integer, intent(out) :: rank
        logical, intent(out) :: is_double
        integer(hid_t) :: did, sid, tid
        integer(hsize_t) :: maxdims(7)
        integer :: ierr, cls
        integer(size_t) :: sz
        rank = -1; dims = 0; is_double = .false.
        if (.not. self%exists(name)) return
        call h5dopen_f(self%fid, name, did, ierr)
        if (ierr /= 0) return
        call h5dget_space_f(did, sid, ierr)
        call h5sget_simple_extent_ndims_f(sid, rank, ierr)
        call h5sget_simple_extent_dims_f(sid, dims(1:max(rank, 1)), maxdims(1:max(rank, 1)), ierr)
        call h5dget_type_f(did, tid, ierr)
        call h5tget_class_f(tid, cls, ierr)
        call h5tget_size_f(tid, sz, ierr)
        is_double = cls == H5T_FLOAT_F .and. sz == 8
        call h5tclose_f(tid, ierr); call h5sclose_f(sid, ierr); call h5dclose_f(did, ierr)
    end subroutine h5_shape_of

    subroutine h5_read_r2(self, name, value, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        real(dp), intent(out) :: value(:, :)
        type(error_t), allocatable, intent(out) :: error
        integer(hid_t) :: did
        integer :: ierr, ie
        integer(hsize_t) :: dims(2)
        dims = shape(value, hsize_t)
        call h5dopen_f(self%fid, name, did, ierr)
        if (ierr /= 0) then
            call fatal_error(error, "veslide:hdf5:read: no dataset "//name//" in "//self%path); return
        end if
        call h5dread_f(did, H5T_NATIVE_DOUBLE, value, dims, ierr)
        call h5dclose_f(did, ie)
        if (ierr /= 0) call fatal_error(error, "veslide:hdf5:read: cannot read "//name//" in "//self%path)
    end subroutine h5_read_r2

    subroutine h5_read_r0(self, name, value, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        real(dp), intent(out) :: value
        type(error_t), allocatable, intent(out) :: error
        integer(hid_t) :: did
        integer :: ierr, ie
        integer(hsize_t) :: dims(0)
        call h5dopen_f(self%fid, name, did, ierr)
        if (ierr /= 0) then
            call fatal_error(error, "veslide:hdf5:read: no dataset "//name//" in "//self%path); return
        end if
        call h5dread_f(did, H5T_NATIVE_DOUBLE, value, dims, ierr)
        call h5dclose_f(did, ie)
        if (ierr /= 0) call fatal_error(error, "veslide:hdf5:read: cannot read "//name//" in "//self%path)
    end subroutine h5_read_r0

    logical function h5_attr_exists(self, obj, name) result(yes)
        class(h5file_t), intent(in) :: self
        character(len=*), intent(in) :: obj, name
        integer :: ierr
        call h5aexists_by_name_f(self%fid, obj, name, yes, ierr)
        if (ierr /= 0) yes = .false.
    end function h5_attr_exists

    subroutine h5_read_attr_r0(self, obj, name, value, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: obj, name
        real(dp), intent(out) :: value
        type(error_t), allocatable, intent(out) :: error
        integer(hid_t) :: aid
        integer :: ierr, ie
        integer(hsize_t) :: dims(1) = [1]
        call h5aopen_by_name_f(self%fid, obj, name, aid, ierr)
        if (ierr /= 0) then
            call fatal_error(error, "veslide:hdf5:read: no attribute "//obj//"@"//name); return
        end if
        call h5aread_f(aid, H5T_NATIVE_DOUBLE, value, dims, ierr)
        call h5aclose_f(aid, ie)
        if (ierr /= 0) call fatal_error(error, "veslide:hdf5:read: cannot read attribute "//obj//"@"//name)
    end subroutine h5_read_attr_r0

end module veslide_hdf5
