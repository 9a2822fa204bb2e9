!> Collective writes of fields on a distributed grid, through HDF5's parallel (MPI-IO) driver:
!> every process opens the file together and writes its own rows of each (nx, ny) dataset in one
!> collective transfer. The rest of a result file (scalars, strings, tables, attributes) is
!> written afterwards by the first process alone, through `h5file_t`, so the file has the layout
!> of a serial run. Only in the MPI build (-DVESLIDE_MPI, linked to the parallel HDF5).
module veslide_hdf5_parallel
    use, intrinsic :: iso_c_binding, only: c_loc, c_ptr
    use hdf5
    use veslide_kinds, only: dp
    use veslide_error, only: error_t, io_error
    use veslide_grid, only: grid_t
    use veslide_hdf5, only: h5file_t
#ifdef VESLIDE_MPI
    use mpi_f08, only: MPI_INFO_NULL
#endif
    implicit none
    private
    public :: create_collective, write_rows

contains

    !> Create (truncate) `path` on every process of the grid at once
    subroutine create_collective(f, path, grid, error)
        type(h5file_t), intent(inout) :: f
        character(len=*), intent(in) :: path
        type(grid_t), intent(in) :: grid
        type(error_t), allocatable, intent(out) :: error
#ifdef VESLIDE_MPI
        integer(hid_t) :: fapl
        integer :: ierr, ie
        call h5open_f(ierr)
        call h5pcreate_f(H5P_FILE_ACCESS_F, fapl, ierr)
        call h5pset_fapl_mpio_f(fapl, grid%comm, MPI_INFO_NULL%MPI_VAL, ierr)
        call h5fcreate_f(path, H5F_ACC_TRUNC_F, f%fid, ierr, access_prp=fapl)
        call h5pclose_f(fapl, ie)
        f%path = path
        if (ierr /= 0) then
            f%fid = -1
            call io_error(error, "veslide:hdf5:create_collective: cannot create '"//path//"'")
        end if
#else
        call io_error(error, "veslide:hdf5:create_collective: '"//path//"' of a distributed grid needs"// &
                         " the MPI build")
        f%fid = -1
#endif
    end subroutine create_collective

    !> Dataset `name` (nx, ny) from every process's rows `values` (nx, ny_local), collectively
    subroutine write_rows(f, grid, name, values, error)
        type(h5file_t), intent(inout) :: f
        type(grid_t), intent(in) :: grid
        character(len=*), intent(in) :: name
        real(dp), intent(in), target, contiguous :: values(:, :)
        type(error_t), allocatable, intent(out) :: error
#ifdef VESLIDE_MPI
        integer(hid_t) :: fspace, mspace, did, lcpl, xfer
        integer(hsize_t) :: dims(2), offset(2), count(2)
        integer :: ierr, ie
        real(dp), target :: dummy(1)
        type(c_ptr) :: buf
        dims = [int(grid%nx, hsize_t), int(grid%ny, hsize_t)]
        offset = [0_hsize_t, int(grid%j0, hsize_t)]
        count = [int(grid%nx, hsize_t), int(grid%ny_local, hsize_t)]
        call h5screate_simple_f(2, dims, fspace, ierr)
        call h5pcreate_f(H5P_LINK_CREATE_F, lcpl, ie)
        call h5pset_create_inter_group_f(lcpl, 1, ie)
        call h5dcreate_f(f%fid, name, H5T_NATIVE_DOUBLE, fspace, did, ierr, lcpl_id=lcpl)
        call h5pclose_f(lcpl, ie)
        if (ierr /= 0) then
            call h5sclose_f(fspace, ie)
            call io_error(error, "veslide:hdf5:write_rows: cannot create "//name//" in "//f%path); return
        end if
        if (grid%ny_local > 0) then
            call h5sselect_hyperslab_f(fspace, H5S_SELECT_SET_F, offset, count, ierr)
            call h5screate_simple_f(2, count, mspace, ie)
            buf = c_loc(values)
        else
            call h5sselect_none_f(fspace, ierr)
            call h5screate_simple_f(1, [1_hsize_t], mspace, ie)
            call h5sselect_none_f(mspace, ie)
            buf = c_loc(dummy)
        end if
        call h5pcreate_f(H5P_DATASET_XFER_F, xfer, ie)
        call h5pset_dxpl_mpio_f(xfer, H5FD_MPIO_COLLECTIVE_F, ie)
        call h5dwrite_f(did, H5T_NATIVE_DOUBLE, buf, ierr, mem_space_id=mspace, file_space_id=fspace, xfer_prp=xfer)
        call h5pclose_f(xfer, ie)
        call h5sclose_f(mspace, ie)
        call h5sclose_f(fspace, ie)
        call h5dclose_f(did, ie)
        if (ierr /= 0 .or. ie /= 0) call io_error(error, "veslide:hdf5:write_rows: cannot write "//name//" in "//f%path)
#else
        call io_error(error, "veslide:hdf5:write_rows: "//name//" of a distributed grid needs the MPI build")
#endif
    end subroutine write_rows

end module veslide_hdf5_parallel
