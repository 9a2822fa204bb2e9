!> A thin HDF5 file handle in the shape of h5fortran's API, over the HDF5 Fortran library.
!>
!> Datasets are created with their intermediate groups. Fortran arrays are stored as they are:
!> a Fortran (nx, ny) array reads in h5py with shape (ny, nx). Strings (datasets and attributes)
!> are variable-length UTF-8, so h5py returns `str` for attributes. Integers are 64-bit.
!> Tables are 1-D compound datasets of 8-byte columns (float64 or int64), with a `units`
!> attribute listing the units of every column in order: `pandas.DataFrame(f[name][()])` reads
!> one in a call. Every write goes through one private routine per object kind (dataset,
!> attribute), dispatched by the generic `write` and `writeattr`.
module veslide_hdf5
    use, intrinsic :: iso_c_binding, only: c_ptr, c_loc, c_char, c_null_char, c_int, c_null_ptr
    use hdf5
    use veslide_kinds, only: dp, i8
    use veslide_error, only: error_t, io_error
    use veslide_strings, only: c_string
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
        procedure :: flush => h5_flush
        procedure :: delete => h5_delete
        procedure :: copy_from => h5_copy_from
        generic :: write => write_r0, write_i0, write_r1, write_r2, write_text, write_text_list
        procedure, private :: write_r0, write_i0, write_r1, write_r2, write_text, write_text_list
        generic :: writeattr => attr_text, attr_r0, attr_i0, attr_text_list, attr_i1
        procedure, private :: attr_text, attr_r0, attr_i0, attr_text_list, attr_i1
        procedure :: write_table => h5_write_table
        procedure :: append_row => h5_append_row
        procedure :: read_table => h5_read_table
        procedure :: read_r0 => h5_read_r0
        procedure :: read_i0 => h5_read_i0
        procedure :: read_r2 => h5_read_r2
        procedure :: read_r2_rows => h5_read_r2_rows
        procedure :: read_r2_block => h5_read_r2_block
        procedure :: read_text => h5_read_text
        procedure :: shape_of => h5_shape_of
        procedure :: attr_exists => h5_attr_exists
        procedure :: read_attr_r0 => h5_read_attr_r0
        procedure :: read_attr_text => h5_read_attr_text
        procedure :: read_attr_text_list => h5_read_attr_text_list
        final :: h5_finalize
    end type h5file_t

    logical, save :: lib_open = .false.

    interface
        integer(c_int) function c_h5free_memory(p) bind(c, name='H5free_memory')
            import :: c_ptr, c_int
            type(c_ptr), value :: p
        end function c_h5free_memory
    end interface

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

    !> Open `path`: action 'w' creates or truncates, 'r' reads, 'rw' reads and writes
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
        case ('rw')
            call h5fopen_f(path, H5F_ACC_RDWR_F, self%fid, ierr)
        case default
            ierr = -1
        end select
        if (ierr /= 0) then
            self%fid = -1
            call io_error(error, "veslide:hdf5:open: cannot open '"//path//"' for '"//action//"'")
        end if
    end subroutine h5_open

    logical function h5_is_open(self) result(yes)
        class(h5file_t), intent(in) :: self
        yes = self%fid >= 0
    end function h5_is_open

    !> Close the file; `error` reports a failure to write what was pending (a full disk)
    subroutine h5_close(self, error)
        class(h5file_t), intent(inout) :: self
        type(error_t), allocatable, intent(out), optional :: error
        integer :: ierr
        if (self%fid < 0) return
        call h5fclose_f(self%fid, ierr)
        self%fid = -1
        if (ierr /= 0 .and. present(error)) &
            call io_error(error, "veslide:hdf5:close: cannot finish writing '"//self%path//"'")
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

    !> Push what was written to disk (a reader of an unfinished study sees every finished case)
    subroutine h5_flush(self, error)
        class(h5file_t), intent(inout) :: self
        type(error_t), allocatable, intent(out), optional :: error
        integer :: ierr
        if (.not. self%is_open()) return
        call h5fflush_f(self%fid, H5F_SCOPE_GLOBAL_F, ierr)
        if (ierr /= 0 .and. present(error)) &
            call io_error(error, "veslide:hdf5:flush: cannot write '"//self%path//"'")
    end subroutine h5_flush

    !> Remove the link `name` (a dataset or a group), if it exists
    subroutine h5_delete(self, name)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        integer :: ierr
        if (self%exists(name)) call h5ldelete_f(self%fid, name, ierr)
    end subroutine h5_delete

    !> Copy object `name` (with everything below it) of the open file `src` to `dst_name` here
    subroutine h5_copy_from(self, src, name, dst_name, error)
        class(h5file_t), intent(inout) :: self
        type(h5file_t), intent(in) :: src
        character(len=*), intent(in) :: name, dst_name
        type(error_t), allocatable, intent(out) :: error
        integer(hid_t) :: lcpl
        integer :: ierr, ie
        call h5pcreate_f(H5P_LINK_CREATE_F, lcpl, ierr)
        call h5pset_create_inter_group_f(lcpl, 1, ierr)
        call h5ocopy_f(src%fid, name, self%fid, dst_name, ierr, lcpl_id=lcpl)
        call h5pclose_f(lcpl, ie)
        if (ierr /= 0) call io_error(error, "veslide:hdf5:copy: cannot copy "//name//" of "//src%path// &
                                        " to "//dst_name//" in "//self%path)
    end subroutine h5_copy_from

    ! ---------------------------------------------------------------- writing datasets

    !> Create dataset `name` of type `dtype` and dimensions `dims` (none: scalar) and write `buf`
    subroutine write_raw(self, name, dtype, dims, buf, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        integer(hid_t), intent(in) :: dtype
        integer(hsize_t), intent(in) :: dims(:)
        type(c_ptr), intent(in) :: buf
        type(error_t), allocatable, intent(out) :: error
        integer(hid_t) :: sid, lcpl, did
        integer :: ierr, ie
        if (.not. self%is_open()) then
            call io_error(error, "veslide:hdf5:write: file not open for "//name); return
        end if
        if (size(dims) == 0) then
            call h5screate_f(H5S_SCALAR_F, sid, ierr)
        else
            call h5screate_simple_f(size(dims), dims, sid, ierr)
        end if
        call h5pcreate_f(H5P_LINK_CREATE_F, lcpl, ie)
        call h5pset_create_inter_group_f(lcpl, 1, ie)
        call h5dcreate_f(self%fid, name, dtype, sid, did, ierr, lcpl_id=lcpl)
        call h5pclose_f(lcpl, ie)
        call h5sclose_f(sid, ie)
        if (ierr /= 0) then
            call io_error(error, "veslide:hdf5:write: cannot create "//name//" in "//self%path); return
        end if
        ierr = 0
        if (product(dims) > 0) call h5dwrite_f(did, dtype, buf, ierr)     ! (an empty dataset: nothing to write)
        call h5dclose_f(did, ie)
        if (ierr /= 0 .or. ie /= 0) call io_error(error, "veslide:hdf5:write: cannot write "//name//" in "//self%path)
    end subroutine write_raw

    subroutine write_r0(self, name, value, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        real(dp), intent(in), target :: value
        type(error_t), allocatable, intent(out) :: error
        integer(hsize_t) :: dims(0)
        call write_raw(self, name, H5T_NATIVE_DOUBLE, dims, c_loc(value), error)
    end subroutine write_r0

    subroutine write_i0(self, name, value, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        integer(i8), intent(in), target :: value
        type(error_t), allocatable, intent(out) :: error
        integer(hsize_t) :: dims(0)
        call write_raw(self, name, H5T_STD_I64LE, dims, c_loc(value), error)
    end subroutine write_i0

    subroutine write_r1(self, name, value, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        real(dp), intent(in), target, contiguous :: value(:)
        type(error_t), allocatable, intent(out) :: error
        call write_raw(self, name, H5T_NATIVE_DOUBLE, shape(value, hsize_t), c_loc(value), error)
    end subroutine write_r1

    subroutine write_r2(self, name, value, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        real(dp), intent(in), target, contiguous :: value(:, :)
        type(error_t), allocatable, intent(out) :: error
        call write_raw(self, name, H5T_NATIVE_DOUBLE, shape(value, hsize_t), c_loc(value), error)
    end subroutine write_r2

    !> Scalar string dataset (variable-length UTF-8)
    subroutine write_text(self, name, value, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: name, value
        type(error_t), allocatable, intent(out) :: error
        character(len=:, kind=c_char), allocatable, target :: cs
        type(c_ptr), target :: ptr
        integer(hid_t) :: tid
        integer(hsize_t) :: dims(0)
        integer :: ie
        cs = value//c_null_char; ptr = c_loc(cs)
        call vl_string_type(tid)
        call write_raw(self, name, tid, dims, c_loc(ptr), error)
        call h5tclose_f(tid, ie)
    end subroutine write_text

    !> 1-D string dataset (variable-length UTF-8), each value trimmed; an empty list gives an
    !> empty dataset
    subroutine write_text_list(self, name, values, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: name, values(:)
        type(error_t), allocatable, intent(out) :: error
        character(len=len(values) + 1, kind=c_char), allocatable, target :: cs(:)
        type(c_ptr), allocatable, target :: ptrs(:)
        integer(hid_t) :: tid
        integer :: ie, k
        allocate (cs(max(size(values), 1)), ptrs(max(size(values), 1)))
        ptrs = c_null_ptr
        do k = 1, size(values)
            cs(k) = trim(values(k))//c_null_char
            ptrs(k) = c_loc(cs(k))
        end do
        call vl_string_type(tid)
        call write_raw(self, name, tid, [int(size(values), hsize_t)], c_loc(ptrs), error)
        call h5tclose_f(tid, ie)
    end subroutine write_text_list

    !> Variable-length UTF-8 string type (close it with h5tclose_f)
    subroutine vl_string_type(tid)
        integer(hid_t), intent(out) :: tid
        integer :: ierr
        call h5tcopy_f(H5T_C_S1, tid, ierr)
        call h5tset_size_f(tid, -1_size_t, ierr)       ! H5T_VARIABLE
        call h5tset_cset_f(tid, H5T_CSET_UTF8_F, ierr)
    end subroutine vl_string_type

    ! ---------------------------------------------------------------- attributes

    !> Attribute `name` of object `obj` ('/' for the root) of type `dtype`, `n` values (0: scalar)
    subroutine attr_raw(self, obj, name, dtype, n, buf, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: obj, name
        integer(hid_t), intent(in) :: dtype
        integer, intent(in) :: n
        type(c_ptr), intent(in) :: buf
        type(error_t), allocatable, intent(out) :: error
        integer(hid_t) :: oid, sid, aid
        integer :: ierr, ie
        logical :: there
        call h5oopen_f(self%fid, obj, oid, ierr)
        if (ierr /= 0) then
            call io_error(error, "veslide:hdf5:writeattr: no object "//obj//" in "//self%path); return
        end if
        if (n == 0) then
            call h5screate_f(H5S_SCALAR_F, sid, ierr)
        else
            call h5screate_simple_f(1, [int(n, hsize_t)], sid, ierr)
        end if
        call h5aexists_f(oid, name, there, ie)
        if (there) call h5adelete_f(oid, name, ie)
        call h5acreate_f(oid, name, dtype, sid, aid, ierr)
        if (ierr == 0) call h5awrite_f(aid, dtype, buf, ierr)
        if (ierr /= 0) call io_error(error, "veslide:hdf5:writeattr: "//obj//"@"//name//" in "//self%path)
        call h5aclose_f(aid, ie); call h5sclose_f(sid, ie); call h5oclose_f(oid, ie)
    end subroutine attr_raw

    subroutine attr_text(self, obj, name, value, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: obj, name, value
        type(error_t), allocatable, intent(out) :: error
        character(len=:, kind=c_char), allocatable, target :: cs
        type(c_ptr), target :: ptr
        integer(hid_t) :: tid
        integer :: ie
        cs = value//c_null_char; ptr = c_loc(cs)
        call vl_string_type(tid)
        call attr_raw(self, obj, name, tid, 0, c_loc(ptr), error)
        call h5tclose_f(tid, ie)
    end subroutine attr_text

    !> A 1-D attribute of strings (each trimmed), e.g. the units of the columns of a table
    subroutine attr_text_list(self, obj, name, values, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: obj, name, values(:)
        type(error_t), allocatable, intent(out) :: error
        character(len=len(values) + 1, kind=c_char), allocatable, target :: cs(:)
        type(c_ptr), allocatable, target :: ptrs(:)
        integer(hid_t) :: tid
        integer :: ie, k
        allocate (cs(size(values)), ptrs(size(values)))
        do k = 1, size(values)
            cs(k) = trim(values(k))//c_null_char
            ptrs(k) = c_loc(cs(k))
        end do
        call vl_string_type(tid)
        call attr_raw(self, obj, name, tid, size(values), c_loc(ptrs), error)
        call h5tclose_f(tid, ie)
    end subroutine attr_text_list

    subroutine attr_r0(self, obj, name, value, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: obj, name
        real(dp), intent(in), target :: value
        type(error_t), allocatable, intent(out) :: error
        call attr_raw(self, obj, name, H5T_NATIVE_DOUBLE, 0, c_loc(value), error)
    end subroutine attr_r0

    subroutine attr_i0(self, obj, name, value, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: obj, name
        integer(i8), intent(in), target :: value
        type(error_t), allocatable, intent(out) :: error
        call attr_raw(self, obj, name, H5T_STD_I64LE, 0, c_loc(value), error)
    end subroutine attr_i0

    subroutine attr_i1(self, obj, name, values, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: obj, name
        integer(i8), intent(in), target, contiguous :: values(:)
        type(error_t), allocatable, intent(out) :: error
        call attr_raw(self, obj, name, H5T_STD_I64LE, size(values), c_loc(values), error)
    end subroutine attr_i1

    ! ---------------------------------------------------------------- tables

    !> Compound type of 8-byte columns, float64 or int64 (is_int); column names must be unique
    subroutine table_type(columns, is_int, tid, error)
        character(len=*), intent(in) :: columns(:)
        logical, intent(in) :: is_int(:)
        integer(hid_t), intent(out) :: tid
        type(error_t), allocatable, intent(out) :: error
        integer :: ierr, k, ie
        call h5tcreate_f(H5T_COMPOUND_F, int(8*size(columns), size_t), tid, ierr)
        do k = 1, size(columns)
            call h5tinsert_f(tid, trim(columns(k)), int(8*(k - 1), size_t), &
                             merge(H5T_STD_I64LE, H5T_NATIVE_DOUBLE, is_int(k)), ierr)
            if (ierr /= 0) then
                call h5tclose_f(tid, ie)
                call io_error(error, "veslide:hdf5:table: column '"//trim(columns(k))//"' cannot be added"// &
                                 " (a repeated name?)"); return
            end if
        end do
    end subroutine table_type

    !> A table as a 1-D compound dataset; `bits(ncol, nrow)` holds each cell's 8 bytes (a real
    !> column through transfer(x, 0_i8), an integer column as the integer itself). An existing
    !> dataset of that name is replaced. `units` become the attribute `units`.
    subroutine h5_write_table(self, name, columns, units, is_int, bits, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: name, columns(:), units(:)
        logical, intent(in) :: is_int(:)
        integer(i8), intent(in), target, contiguous :: bits(:, :)
        type(error_t), allocatable, intent(out) :: error
        integer(hid_t) :: tid
        integer :: ie
        call self%delete(name)
        call table_type(columns, is_int, tid, error); if (allocated(error)) return
        call write_raw(self, name, tid, [int(size(bits, 2), hsize_t)], c_loc(bits), error)
        call h5tclose_f(tid, ie)
        if (allocated(error)) return
        call self%writeattr(name, 'units', units, error)
    end subroutine h5_write_table

    !> Append one row (as in write_table) to a table, created extendible on the first row; each
    !> row costs its own size, so a long study does not rewrite its table
    subroutine h5_append_row(self, name, columns, units, is_int, bits, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: name, columns(:), units(:)
        logical, intent(in) :: is_int(:)
        integer(i8), intent(in), target, contiguous :: bits(:)
        type(error_t), allocatable, intent(out) :: error
        integer(hid_t) :: tid, did, sid, msid, lcpl, dcpl
        integer(hsize_t) :: dims(1), maxdims(1), start(1), cnt(1)
        integer :: ierr, ie
        logical :: created
        call table_type(columns, is_int, tid, error); if (allocated(error)) return
        created = .not. self%exists(name)
        if (created) then
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
            call io_error(error, "veslide:hdf5:append_row: cannot open "//name//" in "//self%path); return
        end if
        call h5dget_space_f(did, sid, ierr)
        call h5sget_simple_extent_dims_f(sid, dims, maxdims, ie)
        call h5sclose_f(sid, ie)
        start = dims; cnt = [1_hsize_t]
        dims = dims + 1
        call h5dset_extent_f(did, dims, ierr)
        call h5dget_space_f(did, sid, ie)
        call h5sselect_hyperslab_f(sid, H5S_SELECT_SET_F, start, cnt, ie)
        call h5screate_simple_f(1, cnt, msid, ie)
        if (ierr == 0) call h5dwrite_f(did, tid, c_loc(bits), ierr, mem_space_id=msid, file_space_id=sid)
        call h5sclose_f(msid, ie); call h5sclose_f(sid, ie); call h5dclose_f(did, ie); call h5tclose_f(tid, ie)
        if (ierr /= 0) then
            call io_error(error, "veslide:hdf5:append_row: cannot write a row of "//name//" in "//self%path)
            return
        end if
        if (created) call self%writeattr(name, 'units', units, error)
    end subroutine h5_append_row

    !> Read a table of 8-byte columns: names, which are integers, and the cells' bytes (ncol, nrow)
    subroutine h5_read_table(self, name, columns, is_int, bits, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        character(len=64), allocatable, intent(out) :: columns(:)
        logical, allocatable, intent(out) :: is_int(:)
        integer(i8), allocatable, target, intent(out) :: bits(:, :)
        type(error_t), allocatable, intent(out) :: error
        integer(hid_t) :: did, ftid, mtid, sid, mt
        integer(hsize_t) :: dims(1), maxdims(1)
        integer :: ierr, ie, n, k, cls, namelen
        character(len=256) :: cname
        type(c_ptr) :: bufv
        call h5dopen_f(self%fid, name, did, ierr)
        if (ierr /= 0) then
            call io_error(error, "veslide:hdf5:read_table: no table "//name//" in "//self%path); return
        end if
        call h5dget_type_f(did, ftid, ierr)
        call h5tget_nmembers_f(ftid, n, ierr)
        allocate (columns(n), is_int(n))
        call h5tcreate_f(H5T_COMPOUND_F, int(8*n, size_t), mtid, ie)
        do k = 1, n
            call h5tget_member_name_f(ftid, k - 1, cname, namelen, ie)
            columns(k) = cname(1:namelen)
            call h5tget_member_class_f(ftid, k - 1, cls, ie)
            is_int(k) = cls == H5T_INTEGER_F
            mt = merge(H5T_STD_I64LE, H5T_NATIVE_DOUBLE, is_int(k))
            call h5tinsert_f(mtid, trim(columns(k)), int(8*(k - 1), size_t), mt, ie)
        end do
        call h5dget_space_f(did, sid, ie)
        call h5sget_simple_extent_dims_f(sid, dims, maxdims, ie)
        call h5sclose_f(sid, ie)
        allocate (bits(n, dims(1)))
        bufv = c_loc(bits)
        if (dims(1) > 0) call h5dread_f(did, mtid, bufv, ierr)
        call h5tclose_f(mtid, ie); call h5tclose_f(ftid, ie); call h5dclose_f(did, ie)
        if (ierr /= 0) call io_error(error, "veslide:hdf5:read_table: cannot read "//name//" in "//self%path)
    end subroutine h5_read_table

    ! ---------------------------------------------------------------- reading

    subroutine read_raw(self, name, dtype, buf, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        integer(hid_t), intent(in) :: dtype
        type(c_ptr), intent(in) :: buf
        type(error_t), allocatable, intent(out) :: error
        integer(hid_t) :: did
        integer :: ierr, ie
        type(c_ptr) :: bufv
        bufv = buf
        call h5dopen_f(self%fid, name, did, ierr)
        if (ierr /= 0) then
            call io_error(error, "veslide:hdf5:read: no dataset "//name//" in "//self%path); return
        end if
        call h5dread_f(did, dtype, bufv, ierr)
        call h5dclose_f(did, ie)
        if (ierr /= 0) call io_error(error, "veslide:hdf5:read: cannot read "//name//" in "//self%path)
    end subroutine read_raw

    subroutine h5_read_r0(self, name, value, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        real(dp), intent(out), target :: value
        type(error_t), allocatable, intent(out) :: error
        call read_raw(self, name, H5T_NATIVE_DOUBLE, c_loc(value), error)
    end subroutine h5_read_r0

    subroutine h5_read_i0(self, name, value, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        integer(i8), intent(out), target :: value
        type(error_t), allocatable, intent(out) :: error
        call read_raw(self, name, H5T_STD_I64LE, c_loc(value), error)
    end subroutine h5_read_i0

    !> A 2-D float64 dataset into `value`, whose shape must be the dataset's (see shape_of)
    subroutine h5_read_r2(self, name, value, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        real(dp), intent(out), target, contiguous :: value(:, :)
        type(error_t), allocatable, intent(out) :: error
        call read_raw(self, name, H5T_NATIVE_DOUBLE, c_loc(value), error)
    end subroutine h5_read_r2

    !> Rows j0+1 .. j0+size(value, 2) of the 2-D float64 dataset `name` (a hyperslab: a
    !> process of a distributed grid reads its own rows only)
    subroutine h5_read_r2_rows(self, name, value, j0, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        real(dp), intent(out), target, contiguous :: value(:, :)
        integer, intent(in) :: j0
        type(error_t), allocatable, intent(out) :: error
        call self%read_r2_block(name, value, 0, j0, error)
    end subroutine h5_read_r2_rows

    !> The block of the 2-D float64 dataset `name` (Fortran order (n1, n2)) whose first element
    !> is (i0+1, j0+1), of the shape of `value` (a hyperslab)
    subroutine h5_read_r2_block(self, name, value, i0, j0, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        real(dp), intent(out), target, contiguous :: value(:, :)
        integer, intent(in) :: i0, j0
        type(error_t), allocatable, intent(out) :: error
        integer(hid_t) :: did, fspace, mspace
        integer(hsize_t) :: count(2)
        integer :: ierr, ie
        type(c_ptr) :: buf
        if (size(value) == 0) return
        call h5dopen_f(self%fid, name, did, ierr)
        if (ierr /= 0) then
            call io_error(error, "veslide:hdf5:read: no dataset "//name//" in "//self%path); return
        end if
        count = shape(value, hsize_t)
        call h5dget_space_f(did, fspace, ie)
        call h5sselect_hyperslab_f(fspace, H5S_SELECT_SET_F, [int(i0, hsize_t), int(j0, hsize_t)], count, ierr)
        call h5screate_simple_f(2, count, mspace, ie)
        buf = c_loc(value)
        if (ierr == 0) call h5dread_f(did, H5T_NATIVE_DOUBLE, buf, ierr, mem_space_id=mspace, file_space_id=fspace)
        call h5sclose_f(mspace, ie); call h5sclose_f(fspace, ie); call h5dclose_f(did, ie)
        if (ierr /= 0) call io_error(error, "veslide:hdf5:read: cannot read a block of "//name//" in "//self%path)
    end subroutine h5_read_r2_block

    !> A scalar string dataset (variable-length, as write_text stores it)
    subroutine h5_read_text(self, name, value, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: name
        character(len=:), allocatable, intent(out) :: value
        type(error_t), allocatable, intent(out) :: error
        type(c_ptr), target :: ptr
        integer(hid_t) :: tid
        integer :: ie
        call vl_string_type(tid)
        call read_raw(self, name, tid, c_loc(ptr), error)
        call h5tclose_f(tid, ie)
        if (allocated(error)) return
        value = c_string(ptr)
        ie = c_h5free_memory(ptr)
    end subroutine h5_read_text

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

    logical function h5_attr_exists(self, obj, name) result(yes)
        class(h5file_t), intent(in) :: self
        character(len=*), intent(in) :: obj, name
        integer :: ierr
        call h5aexists_by_name_f(self%fid, obj, name, yes, ierr)
        if (ierr /= 0) yes = .false.
    end function h5_attr_exists

    subroutine read_attr_raw(self, obj, name, dtype, buf, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: obj, name
        integer(hid_t), intent(in) :: dtype
        type(c_ptr), intent(in) :: buf
        type(error_t), allocatable, intent(out) :: error
        integer(hid_t) :: aid
        integer :: ierr, ie
        type(c_ptr) :: bufv
        bufv = buf
        call h5aopen_by_name_f(self%fid, obj, name, aid, ierr)
        if (ierr /= 0) then
            call io_error(error, "veslide:hdf5:read: no attribute "//obj//"@"//name//" in "//self%path); return
        end if
        call h5aread_f(aid, dtype, bufv, ierr)
        call h5aclose_f(aid, ie)
        if (ierr /= 0) call io_error(error, "veslide:hdf5:read: cannot read attribute "//obj//"@"//name// &
                                        " in "//self%path)
    end subroutine read_attr_raw

    subroutine h5_read_attr_r0(self, obj, name, value, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: obj, name
        real(dp), intent(out), target :: value
        type(error_t), allocatable, intent(out) :: error
        call read_attr_raw(self, obj, name, H5T_NATIVE_DOUBLE, c_loc(value), error)
    end subroutine h5_read_attr_r0

    !> A scalar string attribute (variable-length, as writeattr stores it)
    subroutine h5_read_attr_text(self, obj, name, value, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: obj, name
        character(len=:), allocatable, intent(out) :: value
        type(error_t), allocatable, intent(out) :: error
        type(c_ptr), target :: ptr
        integer(hid_t) :: tid
        integer :: ie
        call vl_string_type(tid)
        call read_attr_raw(self, obj, name, tid, c_loc(ptr), error)
        call h5tclose_f(tid, ie)
        if (allocated(error)) return
        value = c_string(ptr)
        ie = c_h5free_memory(ptr)
    end subroutine h5_read_attr_text

    !> A 1-D string attribute (as attr_text_list stores it) into `values`, of its length
    subroutine h5_read_attr_text_list(self, obj, name, values, error)
        class(h5file_t), intent(inout) :: self
        character(len=*), intent(in) :: obj, name
        character(len=*), intent(inout) :: values(:)
        type(error_t), allocatable, intent(out) :: error
        type(c_ptr), allocatable, target :: ptrs(:)
        integer(hid_t) :: tid, aid, sid
        integer(hsize_t) :: dims(1), maxdims(1)
        integer :: ie, k, rank
        call h5aopen_by_name_f(self%fid, obj, name, aid, ie)
        if (ie /= 0) then
            call io_error(error, "veslide:hdf5:read: no attribute "//obj//"@"//name//" in "//self%path); return
        end if
        call h5aget_space_f(aid, sid, ie)
        call h5sget_simple_extent_ndims_f(sid, rank, ie)
        dims = 0
        if (rank == 1) call h5sget_simple_extent_dims_f(sid, dims, maxdims, ie)
        call h5sclose_f(sid, ie); call h5aclose_f(aid, ie)
        if (rank /= 1 .or. dims(1) /= size(values)) then
            call io_error(error, "veslide:hdf5:read: attribute "//obj//"@"//name//" in "//self%path// &
                             " does not hold the expected number of strings"); return
        end if
        allocate (ptrs(size(values)))
        call vl_string_type(tid)
        call read_attr_raw(self, obj, name, tid, c_loc(ptrs), error)
        call h5tclose_f(tid, ie)
        if (allocated(error)) return
        do k = 1, size(values)
            values(k) = c_string(ptrs(k))
            ie = c_h5free_memory(ptrs(k))
        end do
    end subroutine h5_read_attr_text_list

end module veslide_hdf5
