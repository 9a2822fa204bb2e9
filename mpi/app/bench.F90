!> veslide-bench-mpi: what a distributed grid costs (never part of the test suite).
!>   mpirun -n R veslide-bench-mpi transforms N [N ...]
!>       per grid: the median time of one distributed r2c + c2r pair, of the global transposes it
!>       contains (one per transform, timed alone with FFTW's MPI transpose of the same data), of
!>       the rest (local 1-D transforms and copies), and of one ordered sum (the solver's reduction)
!>   mpirun -n R veslide-bench-mpi case FILE.nml
!>       the case of FILE.nml on a grid distributed over the R ranks, not written: iterations, FFT
!>       pairs, solve time, time per iteration, the time in transforms and in the solver's
!>       collectives (slowest rank), peak memory per rank against the estimate
program veslide_bench_mpi
    use, intrinsic :: iso_c_binding
    use, intrinsic :: iso_fortran_env, only: stdout => output_unit
    use mpi_f08
    use veslide_kinds, only: dp
    use veslide_error, only: error_t
    use veslide_clock, only: wall_seconds
    use veslide_median, only: median
    use veslide_grid, only: grid_t, new_grid
    use veslide_fftw, only: fft2d_t, distribute_grid
    use veslide_collective, only: ordered_sum, collective_seconds
    use veslide_config, only: config_t, read_config
    use veslide_case, only: case_t, run_case
    use veslide_system, only: peak_memory_bytes
    implicit none
#include "fftw3-mpi.f03"
    character(len=512) :: arg
    integer :: rank, nranks, k, n
    type(error_t), allocatable :: error

    call MPI_Init()
    call MPI_Comm_rank(MPI_COMM_WORLD, rank)
    call MPI_Comm_size(MPI_COMM_WORLD, nranks)
    arg = 'transforms'
    if (command_argument_count() >= 1) call get_command_argument(1, arg)
    select case (trim(arg))
    case ('transforms')
        if (rank == 0) then
            write (stdout, '(a,i0,a)') "ranks: ", nranks, " (one thread each)"
            write (stdout, '(a)') "| ranks | N | FFT pair [ms] | 2 transposes [ms] | local [ms] | ordered sum [us] |", &
                "|---|---|---|---|---|---|"
        end if
        do k = 2, command_argument_count()
            call get_command_argument(k, arg); read (arg, *) n
            call bench_transforms(n)
        end do
    case ('case')
        call get_command_argument(2, arg)
        call bench_case(trim(arg))
    case default
        if (rank == 0) write (stdout, '(a)') "usage: veslide-bench-mpi transforms N [N ...] | case FILE.nml"
    end select
    call MPI_Finalize()

contains

    subroutine check()
        if (allocated(error)) then
            write (stdout, '(a)') error%message
            call MPI_Abort(MPI_COMM_WORLD, 1)
        end if
    end subroutine check


    !> Median over ranks' slowest: every timing is the max over ranks of one repetition
    real(dp) function slowest(t) result(s)
        real(dp), intent(in) :: t
        call MPI_Allreduce(t, s, 1, MPI_DOUBLE_PRECISION, MPI_MAX, MPI_COMM_WORLD)
    end function slowest

    subroutine bench_transforms(n)
        integer, intent(in) :: n
        integer, parameter :: reps = 21
        type(grid_t) :: g
        type(fft2d_t) :: fft
        real(dp) :: tp(reps), tt(reps), ts(reps), t0, tot(5)
        real(dp), allocatable :: rows(:, :)
        real(c_double), pointer :: buf(:)
        type(c_ptr) :: p, plan
        integer(c_intptr_t) :: alloc, ln0, l0s, ln1, l1s
        integer :: r
        call new_grid(g, n, n, 1.0_dp, 1.0_dp, error); call check()
        call distribute_grid(g, MPI_COMM_WORLD%MPI_VAL, error); call check()
        call fft%init(n, n, error, planner='measure', grid=g); call check()
        call random_number(fft%x)
        ! the transpose inside each transform: ny x (nx/2+1) complex values, alone
        alloc = fftw_mpi_local_size_many_transposed(2, [int(n, c_intptr_t), int(n/2 + 1, c_intptr_t)], &
                                                    2_c_intptr_t, FFTW_MPI_DEFAULT_BLOCK, FFTW_MPI_DEFAULT_BLOCK, &
                                                    int(MPI_COMM_WORLD%MPI_VAL, c_int32_t), ln0, l0s, ln1, l1s)
        p = fftw_alloc_real(max(1_c_intptr_t, alloc))
        call c_f_pointer(p, buf, [max(1_c_intptr_t, alloc)])
        plan = fftw_mpi_plan_many_transpose(int(n, c_intptr_t), int(n/2 + 1, c_intptr_t), 2_c_intptr_t, &
                                            FFTW_MPI_DEFAULT_BLOCK, FFTW_MPI_DEFAULT_BLOCK, buf, buf, &
                                            int(MPI_COMM_WORLD%MPI_VAL, c_int32_t), FFTW_MEASURE)
        buf = 1.0_c_double
        allocate (rows(5, g%ny_local)); rows = 1.0_dp
        do r = 1, reps
            call MPI_Barrier(MPI_COMM_WORLD)
            t0 = wall_seconds()
            call fft%forward(); call fft%backward()
            tp(r) = slowest(wall_seconds() - t0)
            call MPI_Barrier(MPI_COMM_WORLD)
            t0 = wall_seconds()
            call fftw_mpi_execute_r2r(plan, buf, buf)
            tt(r) = slowest(wall_seconds() - t0)
            call MPI_Barrier(MPI_COMM_WORLD)
            t0 = wall_seconds()
            call ordered_sum(g, rows, tot)
            ts(r) = slowest(wall_seconds() - t0)
        end do
        if (rank == 0) write (stdout, '("| ",i0," | ",i0," | ",f9.3," | ",f9.3," | ",f9.3," | ",f9.1," |")') &
            nranks, n, 1e3_dp*median(tp), 2e3_dp*median(tt), 1e3_dp*(median(tp) - 2.0_dp*median(tt)), 1e6_dp*median(ts)
        call fftw_destroy_plan(plan)
        call fftw_free(p)
        call fft%destroy()
    end subroutine bench_transforms

    subroutine bench_case(path)
        character(len=*), intent(in) :: path
        type(config_t) :: cfg
        type(case_t) :: c
        real(dp) :: t0, wall, coll, cmax, peak(1), pmin(1), pmax(1)
        integer :: iters, pairs
        call read_config(path, cfg, error); call check()
        t0 = wall_seconds()
        call run_case(cfg, c, error, comm=MPI_COMM_WORLD%MPI_VAL); call check()
        wall = wall_seconds() - t0
        coll = collective_seconds
        call MPI_Allreduce(coll, cmax, 1, MPI_DOUBLE_PRECISION, MPI_MAX, MPI_COMM_WORLD)
        peak = real(peak_memory_bytes(), dp)
        call MPI_Allreduce(peak, pmax, 1, MPI_DOUBLE_PRECISION, MPI_MAX, MPI_COMM_WORLD)
        call MPI_Allreduce(peak, pmin, 1, MPI_DOUBLE_PRECISION, MPI_MIN, MPI_COMM_WORLD)
        iters = c%state%iterations; pairs = c%state%operator_applications
        if (rank == 0) then
            write (stdout, '(a)') "| ranks | N | method | iterations | FFT pairs | solve [s] | per iteration [ms] |"// &
                " collectives [s] | peak memory per rank [MiB] | estimate [MiB] | converged |", &
                "|---|---|---|---|---|---|---|---|---|---|---|"
            write (stdout, '("| ",i0," | ",i0," | ",a," | ",i0," | ",i0," | ",f9.2," | ",f9.2," | ",f8.3," | ",f8.1,"-",f8.1, &
                &" | ",f8.1," | ",l1," |")') nranks, c%grid%nx, c%state%method, iters, pairs, c%solve_seconds, &
                1e3_dp*c%solve_seconds/max(1, iters), cmax, pmin/2.0_dp**20, pmax/2.0_dp**20, &
                real(c%memory_estimate_bytes, dp)/2.0_dp**20, c%state%converged
            write (stdout, '(a,f9.2,a)') "total wall time of the case (surface, kernel, solve, analyses): ", wall, " s"
        end if
    end subroutine bench_case

end program veslide_bench_mpi
