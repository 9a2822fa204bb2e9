!> Checks of the distributed grid on the ranks of MPI_COMM_WORLD (run by mpi/check.sh on 1 to 4
!> ranks; uneven shares on purpose): FFTW's MPI transforms equal the serial ones entry by entry
!> through the grid's spectral index, halo rows are the periodic neighbours, ordered sums equal the
!> serial ordered sum bitwise, extrema and counts are global.
program test_distributed
    use, intrinsic :: iso_fortran_env, only: stdout => output_unit
    use mpi_f08
    use veslide_kinds, only: dp, i8
    use veslide_error, only: error_t
    use veslide_grid, only: grid_t, new_grid
    use veslide_fftw, only: fft2d_t, distribute_grid
    use veslide_collective, only: ordered_sum, global_min, global_max, global_count, halo_rows
    implicit none
    type(grid_t) :: g, gs
    type(fft2d_t) :: fd, fs
    type(error_t), allocatable :: error
    real(dp), allocatable :: full(:, :), ext(:, :), rows(:, :), rows_s(:, :)
    real(dp) :: worst, scale, t(2), ts(2), mn, mx
    integer :: rank, nranks, i, j, a, b, ij(2), nfail, d, n
    integer(i8) :: cnt(1)
    integer, parameter :: sizes(2, 3) = reshape([24, 18, 17, 11, 32, 7], [2, 3])

    call MPI_Init()
    call MPI_Comm_rank(MPI_COMM_WORLD, rank)
    call MPI_Comm_size(MPI_COMM_WORLD, nranks)
    nfail = 0
    do n = 1, size(sizes, 2)
        call new_grid(g, sizes(1, n), sizes(2, n), 0.3_dp, 0.2_dp, error); call check()
        call new_grid(gs, sizes(1, n), sizes(2, n), 0.3_dp, 0.2_dp, error); call check()
        call distribute_grid(g, MPI_COMM_WORLD%MPI_VAL, error); call check()
        call fd%init(g%nx, g%ny, error, planner='estimate', grid=g); call check()
        call fs%init(gs%nx, gs%ny, error, planner='estimate'); call check()
        allocate (full(g%nx, g%ny))
        do j = 1, g%ny
            do i = 1, g%nx
                full(i, j) = sin(0.37_dp*i + 0.11_dp*j*j) + cos(0.5_dp*i*j) + 0.01_dp*i
            end do
        end do
        fd%x = full(:, g%j0 + 1:g%j0 + g%ny_local)
        fs%x = full
        call fd%forward(); call fs%forward()
        scale = maxval(abs(fs%k))
        worst = 0.0_dp
        do b = 1, size(fd%k, 2)
            do a = 1, size(fd%k, 1)
                ij = g%spectral_index(a, b)
                worst = max(worst, abs(fd%k(a, b) - fs%k(ij(1), ij(2)))/scale)
            end do
        end do
        call global_max(g, worst)
        call report("forward transform equals the serial one", worst < 1.0e-14_dp, worst)
        call fd%backward()
        worst = maxval(abs(fd%x - full(:, g%j0 + 1:g%j0 + g%ny_local)), mask=.true.) + 0.0_dp
        if (g%ny_local == 0) worst = 0.0_dp
        call global_max(g, worst)
        call report("round trip", worst < 1.0e-14_dp, worst)

        ! ordered sums: per-row partials (sum and sum of squares), gathered in row order
        allocate (rows(2, g%ny_local), rows_s(2, g%ny))
        do j = 1, g%ny_local
            rows(1, j) = sum(full(:, g%j0 + j)); rows(2, j) = sum(full(:, g%j0 + j)**2)
        end do
        do j = 1, g%ny
            rows_s(1, j) = sum(full(:, j)); rows_s(2, j) = sum(full(:, j)**2)
        end do
        call ordered_sum(g, rows, t)
        call ordered_sum(gs, rows_s, ts)
        call report("ordered sum equals the serial one bitwise", all(t == ts), maxval(abs(t - ts)))

        ! halo rows, deeper than some shares
        do d = 1, 3
            call halo_rows(g, full(:, g%j0 + 1:g%j0 + g%ny_local), d, ext)
            worst = 0.0_dp
            do j = 1 - d, g%ny_local + d
                worst = max(worst, maxval(abs(ext(:, j) - full(:, modulo(g%j0 + j - 1, g%ny) + 1))))
            end do
            call global_max(g, worst)
            call report("halo rows of depth "//achar(48 + d), worst == 0.0_dp, worst)
        end do

        mn = huge(1.0_dp); mx = -huge(1.0_dp); cnt = 0
        if (g%ny_local > 0) then
            mn = minval(full(:, g%j0 + 1:g%j0 + g%ny_local)); mx = maxval(full(:, g%j0 + 1:g%j0 + g%ny_local))
            cnt = count(full(:, g%j0 + 1:g%j0 + g%ny_local) > 0.0_dp)
        end if
        call global_min(g, mn); call global_max(g, mx); call global_count(g, cnt)
        call report("global min, max, count", mn == minval(full) .and. mx == maxval(full) .and. &
                    cnt(1) == count(full > 0.0_dp), 0.0_dp)
        call fd%destroy(); call fs%destroy()
        deallocate (full, rows, rows_s)
    end do
    if (rank == 0) write (stdout, '(a,i0,a,i0,a)') "distributed checks on ", nranks, " ranks: ", nfail, " failed"
    call MPI_Finalize()
    if (nfail > 0) error stop 1

contains

    subroutine check()
        if (allocated(error)) then
            write (stdout, '(a)') error%message
            call MPI_Abort(MPI_COMM_WORLD, 1)
        end if
    end subroutine check

    subroutine report(what, ok, value)
        character(len=*), intent(in) :: what
        logical, intent(in) :: ok
        real(dp), intent(in) :: value
        if (.not. ok) nfail = nfail + 1
        if (rank == 0) write (stdout, '(2x,a,1x,i0,"x",i0,": ",a," [",es9.2,"]")') merge("PASS", "FAIL", ok), &
            g%nx, g%ny, what, value
    end subroutine report

end program test_distributed
