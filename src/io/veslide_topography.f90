!> Measured topographies: a square 2-D float64 dataset of heights [m] in an HDF5 file, with the
!> cell side from the caller or the dataset's `length_m` attribute.
module veslide_topography
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use veslide_kinds, only: dp, i8
    use veslide_error, only: error_t, fatal_error
    use veslide_hdf5, only: h5file_t
    use veslide_system, only: missing_reason
    implicit none
    private
    public :: read_topography, topography_shape

contains

    !> The grid of dataset `dataset` in `file` (n x n), checked like read_topography but without
    !> reading the heights: the size is known before any memory is committed to it
    !> With `length_m` (0 on entry: take the dataset's attribute), the cell side as read_topography
    !> would use it.
    subroutine topography_shape(file, dataset, n, error, length_m)
        character(len=*), intent(in) :: file, dataset
        integer, intent(out) :: n
        type(error_t), allocatable, intent(out) :: error
        real(dp), intent(inout), optional :: length_m
        type(h5file_t) :: f
        call open_dataset(file, dataset, f, n, error)
        if (.not. allocated(error) .and. present(length_m)) call cell_side(f, file, dataset, length_m, error)
        call f%close()
    end subroutine topography_shape

    !> The cell side: `length_m` if > 0, else the dataset's attribute length_m
    subroutine cell_side(f, file, dataset, length_m, error)
        type(h5file_t), intent(inout) :: f
        character(len=*), intent(in) :: file, dataset
        real(dp), intent(inout) :: length_m
        type(error_t), allocatable, intent(out) :: error
        character(len=:), allocatable :: at
        if (length_m /= 0.0_dp) return
        at = "file '"//file//"': "
        if (.not. f%attr_exists(dataset, 'length_m')) then
            call fatal_error(error, at//"the cell side is unknown: set &grid lx_m or a 'length_m' attribute"); return
        end if
        call f%read_attr_r0(dataset, 'length_m', length_m, error)
        if (allocated(error)) return
        if (.not. (length_m > 0.0_dp .and. ieee_is_finite(length_m))) then
            call fatal_error(error, at//"attribute length_m must be > 0")
        end if
    end subroutine cell_side

    !> Open `file` and check that `dataset` is a square 2-D float64 array of at least 2 x 2
    subroutine open_dataset(file, dataset, f, n, error)
        character(len=*), intent(in) :: file, dataset
        type(h5file_t), intent(inout) :: f
        integer, intent(out) :: n
        type(error_t), allocatable, intent(out) :: error
        integer(i8) :: dims(7)
        integer :: rank
        logical :: is_double
        character(len=:), allocatable :: at
        at = "file '"//file//"': "
        n = 0
        if (len(missing_reason(file)) > 0) then
            call fatal_error(error, at//missing_reason(file)); return
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
    !> With `rows` = [j0, n_local], only rows j0+1 .. j0+n_local are read (a process's share of
    !> a distributed grid; the NaN check covers those rows).
    subroutine read_topography(file, dataset, h, length_m, error, rows)
        character(len=*), intent(in) :: file, dataset
        real(dp), allocatable, intent(out) :: h(:, :)
        real(dp), intent(inout) :: length_m
        type(error_t), allocatable, intent(out) :: error
        integer, intent(in), optional :: rows(2)
        type(h5file_t) :: f
        integer :: n
        character(len=:), allocatable :: at
        at = "file '"//file//"': "
        call open_dataset(file, dataset, f, n, error); if (allocated(error)) return
        if (present(rows)) then
            allocate (h(n, rows(2)))
            call f%read_r2_rows(dataset, h, rows(1), error)
        else
            allocate (h(n, n))
            call f%read_r2(dataset, h, error)
        end if
        if (allocated(error)) return
        if (.not. all(ieee_is_finite(h))) then      ! (a distributed grid: this process's rows)
            call fatal_error(error, at//"dataset '"//dataset//"' contains NaN or infinite heights"); return
        end if
        call cell_side(f, file, dataset, length_m, error); if (allocated(error)) return
        call f%close()
    end subroutine read_topography

end module veslide_topography
