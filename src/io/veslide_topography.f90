!> Measured topographies: a 2-D float64 dataset of heights [m] in an HDF5 file, Fortran order
!> (nx, ny) (h5py shape (ny, nx), index [iy, ix]; nx and ny may differ), with the cell's sides in
!> the attributes `length_x_m` and `length_y_m` (or `length_m`, the side along x, with square
!> cells), and the record of how the scan was prepared in the text attribute `preparation`
!> (written by the Python package's `veslide.topography`).
module veslide_topography
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use veslide_kinds, only: dp, i8
    use veslide_error, only: error_t, fatal_error
    use veslide_hdf5, only: h5file_t
    use veslide_system, only: missing_reason
    implicit none
    private
    public :: topography_info_t, topography_info, read_topography

    !> What a height file says of itself, before its heights are read
    type :: topography_info_t
        integer :: nx = 0, ny = 0                   !! points along x and y
        real(dp) :: lx_m = 0.0_dp, ly_m = 0.0_dp    !! cell sides from its attributes (0: none)
        character(len=:), allocatable :: preparation !! how it was prepared ('' when not said)
        !> rms over the rows (columns) of the jump between the last and the first point along x
        !> (y), in units of the heights' rms; and the rms step between neighbours inside
        real(dp) :: jump_x = 0.0_dp, jump_y = 0.0_dp, step_x = 0.0_dp, step_y = 0.0_dp
        real(dp) :: rms_m = 0.0_dp                  !! rms of the heights about their mean
        !> the preparation's costs the file states in its attributes `filled_fraction` (the share
        !> of the scan's points that were unmeasured and filled) and `band_slope_variance_removed`
        !> (the share of the slope variance the band removed); -1 when it does not state them
        real(dp) :: filled_fraction = -1.0_dp, band_slope_removed = -1.0_dp
    end type topography_info_t
    integer, parameter :: block_rows = 64           !! rows read at a time for the statistics

contains

    !> The shape, sides, preparation record and edge statistics of dataset `dataset` in `file`,
    !> reading the heights a block of rows at a time (the memory of 64 rows); without the
    !> statistics (`statistics` = .false.) only the metadata are read
    subroutine topography_info(file, dataset, info, error, statistics)
        character(len=*), intent(in) :: file, dataset
        type(topography_info_t), intent(out) :: info
        type(error_t), allocatable, intent(out) :: error
        logical, intent(in), optional :: statistics
        type(h5file_t) :: f
        character(len=:), allocatable :: at
        at = "file '"//file//"': "
        call open_dataset(file, dataset, f, info%nx, info%ny, error); if (allocated(error)) return
        info%preparation = ''
        call read_side('length_x_m', info%lx_m); if (allocated(error)) return
        if (info%lx_m == 0.0_dp) call read_side('length_m', info%lx_m)
        if (allocated(error)) return
        call read_side('length_y_m', info%ly_m); if (allocated(error)) return
        if (info%ly_m == 0.0_dp .and. info%lx_m > 0.0_dp) info%ly_m = info%lx_m*info%ny/info%nx
        if (f%attr_exists(dataset, 'preparation')) then
            call f%read_attr_text(dataset, 'preparation', info%preparation, error)
            if (allocated(error)) then
                call fatal_error(error, at//"attribute 'preparation' is not a text"); return
            end if
        end if
        call read_share('filled_fraction', info%filled_fraction); if (allocated(error)) return
        call read_share('band_slope_variance_removed', info%band_slope_removed); if (allocated(error)) return
        if (present(statistics)) then
            if (.not. statistics) then
                call f%close(); return
            end if
        end if
        call edge_statistics(error)
        call f%close()
    contains
        subroutine read_side(name, length)
            character(len=*), intent(in) :: name
            real(dp), intent(out) :: length
            length = 0.0_dp
            if (.not. f%attr_exists(dataset, name)) return
            call f%read_attr_r0(dataset, name, length, error)
            if (allocated(error)) then
                call fatal_error(error, at//"attribute "//name//" is not a number"); return
            end if
            if (.not. (length > 0.0_dp .and. ieee_is_finite(length))) &
                call fatal_error(error, at//"attribute "//name//" must be > 0 [m]")
        end subroutine read_side

        !> a share (0 to 1) the file states of its preparation in attribute `name`; -1 when absent
        subroutine read_share(name, share)
            character(len=*), intent(in) :: name
            real(dp), intent(out) :: share
            share = -1.0_dp
            if (.not. f%attr_exists(dataset, name)) return
            call f%read_attr_r0(dataset, name, share, error)
            if (allocated(error)) then
                call fatal_error(error, at//"attribute "//name//" is not a number"); return
            end if
            if (.not. (share >= 0.0_dp .and. share <= 1.0_dp)) &
                call fatal_error(error, at//"attribute "//name//" must be a share from 0 to 1")
        end subroutine read_share

        !> rms of the heights, of the steps inside and of the jumps across the edges, from
        !> blocks of rows (sums over the whole grid, then normalised by h_rms)
        subroutine edge_statistics(error)
            type(error_t), allocatable, intent(inout) :: error
            real(dp), allocatable :: b(:, :), first(:), last(:)
            real(dp) :: s1, s2, sx, sy, jx, jy, n, ref
            integer :: j0, m, nx, ny
            nx = info%nx; ny = info%ny
            s1 = 0.0_dp; s2 = 0.0_dp; sx = 0.0_dp; sy = 0.0_dp; jx = 0.0_dp; ref = 0.0_dp
            allocate (first(nx), last(nx))
            do j0 = 0, ny - 1, block_rows
                m = min(block_rows, ny - j0)
                if (allocated(b)) deallocate (b)
                allocate (b(nx, m))
                call f%read_r2_rows(dataset, b, j0, error); if (allocated(error)) return
                if (.not. all(ieee_is_finite(b))) then
                    call fatal_error(error, at//"dataset '"//dataset//"' contains NaN or infinite heights"); return
                end if
                if (j0 == 0) then
                    first = b(:, 1); ref = b(1, 1)   ! moments about a height of the scan: no cancellation
                end if
                if (j0 > 0) sy = sy + sum((b(:, 1) - last)**2)
                s1 = s1 + sum(b - ref); s2 = s2 + sum((b - ref)**2)
                if (nx > 1) sx = sx + sum((b(2:, :) - b(:nx - 1, :))**2)
                if (m > 1) sy = sy + sum((b(:, 2:) - b(:, :m - 1))**2)
                if (nx > 1) jx = jx + sum((b(nx, :) - b(1, :))**2)
                last = b(:, m)
            end do
            n = real(nx, dp)*ny
            info%rms_m = sqrt(max(0.0_dp, s2/n - (s1/n)**2))
            if (.not. info%rms_m > 0.0_dp) return
            jy = sum((first - last)**2)
            if (nx > 1) then
                info%jump_x = sqrt(jx/ny)/info%rms_m; info%step_x = sqrt(sx/(real(nx - 1, dp)*ny))/info%rms_m
            end if
            if (ny > 1) then
                info%jump_y = sqrt(jy/nx)/info%rms_m; info%step_y = sqrt(sy/(real(ny - 1, dp)*nx))/info%rms_m
            end if
        end subroutine edge_statistics
    end subroutine topography_info

    !> Open `file` and check that `dataset` is a 2-D float64 array of at least 2 points, at most
    !> 65536 along each side; its Fortran shape (nx, ny)
    subroutine open_dataset(file, dataset, f, nx, ny, error)
        character(len=*), intent(in) :: file, dataset
        type(h5file_t), intent(inout) :: f
        integer, intent(out) :: nx, ny
        type(error_t), allocatable, intent(out) :: error
        integer(i8) :: dims(7)
        integer :: rank
        logical :: is_double
        character(len=:), allocatable :: at, why
        at = "file '"//file//"': "
        nx = 0; ny = 0
        why = missing_reason(file)
        if (len(why) > 0) then
            call fatal_error(error, at//why); return
        end if
        call f%open(file, 'r', error)
        if (allocated(error)) then
            call fatal_error(error, at//"not a readable HDF5 file"); return
        end if
        call f%shape_of(dataset, dims, rank, is_double)
        if (rank < 0) then
            call fatal_error(error, at//"no dataset '"//dataset//"' (set &surface dataset)"); return
        end if
        if (rank /= 2 .or. .not. is_double .or. dims(1)*dims(2) < 2) then
            call fatal_error(error, at//"dataset '"//dataset// &
                "' must be a 2-D float64 array of heights in metres (h5py shape (ny, nx))"); return
        end if
        if (dims(1) > 65536 .or. dims(2) > 65536) then
            call fatal_error(error, at//"dataset '"//dataset//"' is larger than 65536 points along a side"); return
        end if
        nx = int(dims(1)); ny = int(dims(2))
    end subroutine open_dataset

    !> Heights of dataset `dataset` in `file`, Fortran order (nx, ny). Messages start with the file
    !> name; the caller puts the input that named it in front. With `rows` = [j0, n_local], only
    !> rows j0+1 .. j0+n_local are read (a process's share of a distributed grid).
    subroutine read_topography(file, dataset, h, error, rows)
        character(len=*), intent(in) :: file, dataset
        real(dp), allocatable, intent(out) :: h(:, :)
        type(error_t), allocatable, intent(out) :: error
        integer, intent(in), optional :: rows(2)
        type(h5file_t) :: f
        integer :: nx, ny
        character(len=:), allocatable :: at
        at = "file '"//file//"': "
        call open_dataset(file, dataset, f, nx, ny, error); if (allocated(error)) return
        if (present(rows)) then
            allocate (h(nx, rows(2)))
            call f%read_r2_rows(dataset, h, rows(1), error)
        else
            allocate (h(nx, ny))
            call f%read_r2(dataset, h, error)
        end if
        if (allocated(error)) return
        if (.not. all(ieee_is_finite(h))) then      ! (a distributed grid: this process's rows)
            call fatal_error(error, at//"dataset '"//dataset//"' contains NaN or infinite heights"); return
        end if
        call f%close()
    end subroutine read_topography

end module veslide_topography
