!> Measured topographies: a square 2-D float64 dataset of heights [m] in an HDF5 file, with the
!> cell side from the caller or the dataset's `length_m` attribute.
module veslide_topography
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use veslide_kinds, only: dp, i8
    use veslide_error, only: error_t, fatal_error
    use veslide_hdf5, only: h5file_t
    implicit none
    private
    public :: read_topography, topography_shape

contains

    !> The grid of dataset `dataset` in `file` (n x n), checked like read_topography but without
    !> reading the heights: the size is known before any memory is committed to it
    subroutine topography_shape(file, dataset, n, error)
        character(len=*), intent(in) :: file, dataset
        integer, intent(out) :: n
        type(error_t), allocatable, intent(out) :: error
        type(h5file_t) :: f
        call open_dataset(file, dataset, f, n, error)
        call f%close()
    end subroutine topography_shape

    !> Open `file` and check that `dataset` is a square 2-D float64 array of at least 2 x 2
    subroutine open_dataset(file, dataset, f, n, error)
        character(len=*), intent(in) :: file, dataset
        type(h5file_t), intent(inout) :: f
        integer, intent(out) :: n
        type(error_t), allocatable, intent(out) :: error
        integer(i8) :: dims(7)
        integer :: rank
        logical :: is_double, exists
        character(len=:), allocatable :: at
        at = "file '"//file//"': "
        n = 0
        inquire (file=file, exist=exists)
        if (.not. exists) then
            call fatal_error(error, at//"no such file"); return
        end if
        call f%open(file, 'r', error)
        if (allocated(error)) then
            error%message = at//"not a readable HDF5 file"; return
        end if
        call f%shape_of(dataset, dims, rank, is_double)
        if (rank < 0) then
            call fatal_error(error, at//"no dataset '"//dataset//"' (set &surface dataset)"); return
        end if
        if (rank /= 2 .or. .not. is_double .or. dims(1) /= dims(2) .or. dims(1) < 2) then
            call fatal_error(error, at//"dataset '"//dataset// &
                "' must be a square 2-D float64 array of heights in metres"); return
        end if
        if (dims(1) > 65536) then
            call fatal_error(error, at//"dataset '"//dataset//"' is larger than 65536 x 65536"); return
        end if
        n = int(dims(1))
    end subroutine open_dataset

    !> Heights of dataset `dataset` in `file`; `length_m` is the cell side: on entry the caller's
    !> value (0: take the attribute `length_m` of the dataset), on exit the side used. Messages
    !> start with the file name; the caller puts the input that named it in front.
    subroutine read_topography(file, dataset, h, length_m, error)
        character(len=*), intent(in) :: file, dataset
        real(dp), allocatable, intent(out) :: h(:, :)
        real(dp), intent(inout) :: length_m
        type(error_t), allocatable, intent(out) :: error
        type(h5file_t) :: f
        integer :: n
        character(len=:), allocatable :: at
        at = "file '"//file//"': "
        call open_dataset(file, dataset, f, n, error); if (allocated(error)) return
        allocate (h(n, n))
        call f%read_r2(dataset, h, error)
        if (allocated(error)) return
        if (.not. all(ieee_is_finite(h))) then
            call fatal_error(error, at//"dataset '"//dataset//"' contains NaN or infinite heights"); return
        end if
        if (length_m == 0.0_dp) then
            if (.not. f%attr_exists(dataset, 'length_m')) then
                call fatal_error(error, at//"the cell side is unknown: set &grid lx_m or a 'length_m' attribute"); return
            end if
            call f%read_attr_r0(dataset, 'length_m', length_m, error)
            if (allocated(error)) return
            if (.not. (length_m > 0.0_dp .and. ieee_is_finite(length_m))) then
                call fatal_error(error, at//"attribute length_m must be > 0"); return
            end if
        end if
        call f%close()
    end subroutine read_topography

end module veslide_topography
