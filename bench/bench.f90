!> veslide-bench: measured speed and accuracy (never part of the test suite).
!>   veslide-bench solver [N ...]   solve time, iterations and time per iteration against one
!>                                 FFTW r2c+c2r pair, for the default rough surface at N^2
!>                                 (writes results/bench-solver-N.h5 for bench/tamaas_parity.py)
!>   veslide-bench kernels          Westergaard errors of every kernel variant under refinement
!>   veslide-bench gpu [N ...]      the paper scene (tolerance 1e-8) on the device at N^2 (default
!>                                 1024^2 .. 32768^2, each grid the card holds): solve time, FFT
!>                                 pairs, time per FFT pair spent against one cuFFT pair timed in
!>                                 the same process, peak device memory per cell; then the CPU path
!>                                 on all the machine's cores at VESLIDE_BENCH_CPU (default
!>                                 "2048 4096"). Table on stdout, CSV into VESLIDE_BENCH_CSV
!>                                 (default results/bench-gpu.csv)
!>   veslide-bench adhesion DEVICES ROUNDS N [N ...]  the adhesive solver against the hard wall:
!>                                 the paper scene (tolerance VESLIDE_BENCH_TOLERANCE, default
!>                                 1e-10, both solves; all the machine's cores) with
!>                                 inputs/adhesion/sliding.nml's exponential law and without it, at
!>                                 N^2 on DEVICES ('gpu', 'cpu' or 'both'), ROUNDS interleaved
!>                                 rounds (adhesive, hard wall, on each device in turn): FFT pairs,
!>                                 median solve times and their ratios; with 'both', the device's
!>                                 adhesive solution against the CPU's (pressures, closed cells)
!>   veslide-bench validity [N [ROUNDS]]  the validity measures of a case (veslide_validity)
!>                                 against its solve: the paper scene (tolerance 1e-8, one
!>                                 thread) at N^2 (default 512), solve and measures timed in turn
!>                                 (A B A B), medians and their ratio
!>   veslide-bench prony [N [ROUNDS]]  the cost of a long Prony series: the paper scene's
!>                                 surface, load and speed (one thread) at N^2 (default 512) on a
!>                                 relaxation series of 20 and of 200 terms with the same spectrum
!>                                 (1e-8..1e4 s), the two cases in turn (A B A B): kernel build,
!>                                 solve and whole case, medians and their ratios; sliding along
!>                                 x (the compliance once per column) and at 30 deg (once per mode)
program veslide_bench
    use, intrinsic :: iso_fortran_env, only: stdout => output_unit
    use veslide_kinds, only: dp, pi
    use veslide_error, only: error_t
    use veslide_config, only: config_t, default_config, complete_config
    use veslide_clock, only: now => wall_seconds
    use veslide_median, only: median
    use veslide_grid, only: grid_t, new_grid
    use veslide_fftw, only: fft2d_t
    use veslide_case, only: case_t, run_case
    use veslide_case_file, only: write_case
    use veslide_output, only: prepare_output, release_output, commit_output
    use veslide_material, only: material_t, new_elastic
    use veslide_kernel, only: kernel_t, new_kernel, KERNEL_SPECTRAL, KERNEL_COLLOCATION, &
                              KERNEL_COLLOCATION_ALIAS, KERNEL_GALERKIN
    use veslide_contact, only: contact_problem_t, contact_state_t, new_contact_problem
    use veslide_solver_options, only: solver_options_t
    use veslide_solver, only: solve_contact
    use veslide_surface, only: cosine_surface
    use veslide_analysis, only: contact_area_fraction, contact_area_subcell, mean_separation
    use veslide_scenes, only: hard_case_count, hard_case
    use veslide_device, only: device_enabled, device_count, device_info_t, device_info, device_memory, &
                              device_peak_bytes, device_reset_peak, device_bytes_in_use, device_clock, device_check, &
                              device_profile
    use veslide_transform, only: transform_t
    use veslide_memory, only: device_bytes_per_cell
    use veslide_validity, only: case_validity
    implicit none
    character(len=64) :: arg
    integer :: k, n
    integer, allocatable :: sizes(:)

    arg = 'solver'
    if (command_argument_count() >= 1) call get_command_argument(1, arg)
    select case (trim(arg))
    case ('solver')             ! solver [--method M] N ...: the elastic bench case (method: auto)
        allocate (sizes(0))
        block
            character(len=16) :: method
            method = 'auto'
            k = 2
            do while (k <= command_argument_count())
                call get_command_argument(k, arg)
                if (trim(arg) == '--method') then
                    k = k + 1; call get_command_argument(k, method)
                else
                    read (arg, *) n
                    sizes = [sizes, n]
                end if
                k = k + 1
            end do
            if (size(sizes) == 0) sizes = [256, 512, 1024]
            call bench_solver(sizes, trim(method))
        end block
    case ('kernels')
        call bench_kernels()
    case ('accuracy')           ! accuracy [NMAX [KERNEL]]: the grid study to NMAX (one kernel, or all)
        n = 1024
        if (command_argument_count() >= 2) then
            call get_command_argument(2, arg); read (arg, *) n
        end if
        arg = ''
        if (command_argument_count() >= 3) call get_command_argument(3, arg)
        call bench_accuracy(n, trim(arg))
    case ('scaling')
        call bench_scaling()
    case ('iteration')
        n = 1024
        if (command_argument_count() >= 2) then
            call get_command_argument(2, arg); read (arg, *) n
        end if
        k = 5
        if (command_argument_count() >= 3) then
            call get_command_argument(3, arg); read (arg, *) k
        end if
        call bench_iteration(n, k)
    case ('gpu')
        allocate (sizes(0))
        do k = 2, command_argument_count()
            call get_command_argument(k, arg); read (arg, *) n
            sizes = [sizes, n]
        end do
        if (size(sizes) == 0) sizes = [1024, 2048, 4096, 8192, 16384, 32768]
        call bench_gpu(sizes)
    case ('adhesion')           ! adhesion DEVICES ROUNDS N [N ...]
        block
            character(len=8) :: devices
            devices = 'cpu'
            if (command_argument_count() >= 2) call get_command_argument(2, devices)
            allocate (sizes(0))
            do k = 4, command_argument_count()
                call get_command_argument(k, arg); read (arg, *) n
                sizes = [sizes, n]
            end do
            if (size(sizes) == 0) sizes = [256]
            call bench_adhesion(trim(devices), int_arg(3, 3), sizes)
        end block
    case ('validity')
        call bench_validity(int_arg(2, 512), int_arg(3, 7))
    case ('prony')
        call bench_prony(int_arg(2, 512), int_arg(3, 5))
    case ('hard')
        n = 256
        if (command_argument_count() >= 2) then
            call get_command_argument(2, arg); read (arg, *) n
        end if
        block
            integer :: am, be
            real(dp) :: br, bf
            character(len=16) :: method
            integer :: first, last
            am = -1; be = -1; br = -1; bf = -1; method = ''; first = 1; last = hard_case_count()
            if (command_argument_count() >= 3) then
                call get_command_argument(3, arg); read (arg, *) am
            end if
            if (command_argument_count() >= 4) then
                call get_command_argument(4, arg); read (arg, *) be
            end if
            if (command_argument_count() >= 5) then
                call get_command_argument(5, arg); read (arg, *) br
            end if
            if (command_argument_count() >= 6) then
                call get_command_argument(6, arg); read (arg, *) bf
            end if
            if (command_argument_count() >= 7) call get_command_argument(7, method)
            if (command_argument_count() >= 8) then
                call get_command_argument(8, arg); read (arg, *) first; last = first
            end if
            if (command_argument_count() >= 9) then
                call get_command_argument(9, arg); read (arg, *) last
            end if
            call bench_hard(n, am, be, br, bf, trim(method), first, last)
        end block
    case default
        write (stdout, '(a)') "usage: veslide-bench solver [N ...] | kernels | accuracy [NMAX]", &
            "                     | hard [N [memory [balance_every [ratio [factor [method [first [last]]]]]]]]", &
            "                     | scaling elastic|visco METHOD TOL N [N ...] | iteration [N [ROUNDS]] | gpu [N ...]", &
            "                     | validity [N [ROUNDS]] | adhesion gpu|cpu|both ROUNDS N [N ...]"
        error stop 1
    end select

contains

    !> Command-line argument `i` as an integer, `default` when it is not given
    integer function int_arg(i, default) result(v)
        integer, intent(in) :: i, default
        character(len=64) :: text
        v = default
        if (command_argument_count() < i) return
        call get_command_argument(i, text); read (text, *) v
    end function int_arg

    subroutine check(error)
        type(error_t), allocatable, intent(in) :: error
        if (allocated(error)) then
            write (stdout, '(a)') error%message
            error stop 1
        end if
    end subroutine check

    !> Median time of one r2c + c2r pair (FFTW_MEASURE plans)
    real(dp) function fft_pair_seconds(n) result(tp)
        integer, intent(in) :: n
        type(fft2d_t) :: fft
        type(error_t), allocatable :: error
        real(dp) :: t(31), t0
        integer :: r
        call fft%init(n, n, error, planner='measure'); call check(error)
        call random_number(fft%x)
        do r = 1, size(t)
            t0 = now()
            call fft%forward(); call fft%backward_unscaled()
            t(r) = now() - t0
            fft%x = fft%x/(real(n, dp)**2)
        end do
        tp = median(t)
    end function fft_pair_seconds

    subroutine bench_solver(sizes, method)
        integer, intent(in) :: sizes(:)
        character(len=*), intent(in) :: method
        type(config_t) :: cfg
        type(case_t) :: c
        type(error_t), allocatable :: error
        character(len=:), allocatable :: tmp, out
        character(len=16) :: buf
        real(dp) :: tpair, t(3)
        integer :: k, r, threads, lock
        character(len=16) :: env
        integer :: nenv, stat
        threads = 1
        call get_environment_variable('OMP_NUM_THREADS', env, nenv, stat)
        if (stat == 0 .and. nenv > 0) read (env, *) threads
        write (stdout, '(a,i0,a)') "threads: ", threads, " (OMP_NUM_THREADS; the FFTs run on them); method "//method
        write (stdout, '(a)') "| N | FFT pair [ms] | solve [s] (median of 3) | iterations | FFT pairs | "// &
            "time/iteration [ms] | time/iteration / FFT pair | area | mean gap / h_rms |"
        write (stdout, '(a)') "|---|---|---|---|---|---|---|---|---|"
        do k = 1, size(sizes)
            tpair = fft_pair_seconds(sizes(k))
            write (buf, '(i0)') sizes(k)
            call default_config(cfg, 'bench')
            cfg%grid%nx = sizes(k); cfg%grid%ny = sizes(k); cfg%grid%lx_m = 0.01_dp; cfg%grid%ly_m = 0.01_dp
            cfg%material%model = 'elastic'; cfg%material%young_pa = 1.0e7_dp; cfg%material%poisson = 0.5_dp
            cfg%solver%tolerance = 1.0e-10_dp
            cfg%solver%threads = threads
            cfg%solver%method = method
            cfg%output%file = 'results/bench-solver-'//trim(buf)//'.h5'; cfg%output%overwrite = .true.
            call complete_config(cfg, error); call check(error)
            do r = 1, size(t)
                call run_case(cfg, c, error); call check(error)
                t(r) = c%solve_seconds
            end do
            c%solve_seconds = median(t)
            call prepare_output(cfg%output%file, .true., tmp, lock, error); call check(error)
            call write_case(tmp, c, error); call check(error)
            call commit_output(tmp, cfg%output%file, .true., error); call check(error)
            call release_output(lock, cfg%output%file)
            write (stdout, '("| ",i0," | ",f8.3," | ",f8.3," | ",i0," | ",i0," | ",f8.3," | ",f6.2," | ",f8.5," | ",f8.5," |")') &
                sizes(k), 1e3*tpair, median(t), c%state%iterations, c%state%operator_applications, &
                1e3*median(t)/c%state%iterations, median(t)/c%state%iterations/tpair, &
                contact_area_fraction(c%state%p), mean_separation(c%state%g)/sqrt(sum(c%h**2)/size(c%h))
        end do
    end subroutine bench_solver

    !> The paper scene on the device at each N^2 the card holds, and on the CPU beside it (see the
    !> program's header). The cuFFT pair is timed with the device's default plans and with its
    !> smallest work area; the solve uses the plans the environment chooses
    !> (VESLIDE_CUFFT_WORKAREA). solve [s] is the wall time of the whole solve: the uploads, the
    !> device's allocations and plans, the iteration and the download of p, u and g.
    subroutine bench_gpu(sizes)
        integer, intent(in) :: sizes(:)
        type(device_info_t) :: info
        type(config_t) :: cfg
        type(case_t) :: c
        type(error_t), allocatable :: error
        character(len=256) :: csv_path, cpu_list
        real(dp) :: free_b, total_b, need, tpair(2), work(2), peak, base, tcpu, est(2)
        integer :: k, u, l, st, ncpu
        integer, allocatable :: cpu_sizes(:)
        if (.not. device_enabled .or. device_count() == 0) then
            write (stdout, '(a)') "veslide-bench gpu: no device (a GPU build, gpu/build.sh, on a machine with a GPU)"
            error stop 1
        end if
        call device_info(info, error); call check(error)
        write (stdout, '(a,f0.1,a,i0,a,i0,a,i0)') "device: "//info%name//", ", info%memory_bytes/1.0e9_dp, &
            " GB, driver ", info%driver_version, ", runtime ", info%runtime_version, ", compute capability ", &
            info%compute_capability
        call get_environment_variable('VESLIDE_BENCH_CSV', csv_path, l, st)
        if (st /= 0 .or. l == 0) csv_path = 'results/bench-gpu.csv'
        open (newunit=u, file=trim(csv_path), status='replace', action='write')
        write (u, '(a)') 'backend,n,solve_s,fft_pairs,iterations,pair_ms,pair_min_work_ms,pairs_per_pair,'// &
            'peak_bytes_per_cell,work_bytes_per_cell,work_min_bytes_per_cell,area,friction,converged,transfer_s,'// &
            'estimate_bytes_per_cell,estimate_lean_bytes_per_cell'
        write (stdout, '(a)') "paper scene, tolerance 1e-8, method auto (pdr)"
        write (stdout, '(a)') "| N | solve [s] | of which set-up and transfers [s] | FFT pairs | iterations |"// &
            " cuFFT pair [ms] | per FFT pair spent [cuFFT pairs] | the same without set-up and transfers |"// &
            " peak device [B/cell] | estimate, lean [B/cell] | cuFFT work [B/cell] (min policy) | pair, min work [ms] |"// &
            " area | friction |"
        write (stdout, '(a)') "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
        do k = 1, size(sizes)
            call device_memory(free_b, total_b, error); call check(error)
            need = 110.0_dp*real(sizes(k), dp)**2
            if (free_b >= 0.0_dp .and. need > free_b) then
                write (stdout, '("| ",i0," | skipped: needs about ",f0.1," GB of the ",f0.1," GB free |")') sizes(k), &
                    need/1.0e9_dp, free_b/1.0e9_dp
                cycle
            end if
            call cufft_pair(sizes(k), .false., tpair(1), work(1))
            call cufft_pair(sizes(k), .true., tpair(2), work(2))
            call scene(sizes(k), 'visco', 'auto', 1.0e-8_dp, cfg)
            cfg%solver%device = 'gpu'; cfg%solver%threads = 0; cfg%solver%fft_planner = 'estimate'
            base = device_bytes_in_use()
            call device_reset_peak()
            call device_profile()                  ! (VESLIDE_DEVICE_PROFILE=1: the pair timings' table)
            call run_case(cfg, c, error)
            if (allocated(error)) then
                write (stdout, '("| ",i0," | ",a," |")') sizes(k), error%message
                deallocate (error); cycle
            end if
            peak = (device_peak_bytes() - base)/real(sizes(k), dp)**2
            ! veslide --memory's estimate where the device has room, and the lean one (the refusal's)
            est = [device_bytes_per_cell(c%spec, room=.true.), device_bytes_per_cell(c%spec)]
            write (stdout, '("| ",i0," | ",f9.3," | ",f8.3," | ",i0," | ",i0," | ",f8.3," | ",f6.2," | ",f6.2," | ",f6.1, &
                &" | ",f5.1,", ",f5.1," | ",f5.1," (",f5.1,") | ",f8.3," | ",f9.6," | ",es11.4," |")') sizes(k), &
                c%solve_seconds, c%state%transfer_seconds, c%state%operator_applications, &
                c%state%iterations, 1e3*tpair(1), c%solve_seconds/c%state%operator_applications/tpair(1), &
                (c%solve_seconds - c%state%transfer_seconds)/c%state%operator_applications/tpair(1), peak, est, &
                work(1)/real(sizes(k), dp)**2, work(2)/real(sizes(k), dp)**2, 1e3*tpair(2), &
                contact_area_fraction(c%state%p), -c%force_pa(1)/cfg%load%mean_pressure_pa
            write (u, '(a,",",i0,",",es14.7,",",i0,",",i0,6(",",es14.7),2(",",es17.10),",",l1,3(",",es14.7))') 'gpu', &
                sizes(k), &
                c%solve_seconds, c%state%operator_applications, c%state%iterations, 1e3*tpair(1), 1e3*tpair(2), &
                c%solve_seconds/c%state%operator_applications/tpair(1), peak, work(1)/real(sizes(k), dp)**2, &
                work(2)/real(sizes(k), dp)**2, contact_area_fraction(c%state%p), &
                -c%force_pa(1)/cfg%load%mean_pressure_pa, c%state%converged, c%state%transfer_seconds, est
            flush (stdout); flush (u)
            call device_profile()                  ! (VESLIDE_DEVICE_PROFILE=1: where the solve's time went)
        end do
        call get_environment_variable('VESLIDE_BENCH_CPU', cpu_list, l, st)
        if (st /= 0 .or. l == 0) cpu_list = '2048 4096'
        if (trim(cpu_list) == 'none') cpu_list = ''
        allocate (cpu_sizes(0))
        block
            integer :: ios, v, pos
            character(len=256) :: rest
            rest = cpu_list
            do
                rest = adjustl(rest)
                if (len_trim(rest) == 0) exit
                pos = index(rest, ' ')
                read (rest(1:pos - 1), *, iostat=ios) v
                if (ios == 0) cpu_sizes = [cpu_sizes, v]
                rest = rest(pos:)
            end do
        end block
        write (stdout, '(a)') "the CPU path on the same machine (all its cores; FFTW measured plans)"
        write (stdout, '(a)') "| N | threads | solve [s] | FFT pairs | FFTW pair [ms] | per FFT pair spent [FFTW pairs] |"// &
            " area | friction |"
        write (stdout, '(a)') "|---|---|---|---|---|---|---|---|"
        do k = 1, size(cpu_sizes)
            call scene(cpu_sizes(k), 'visco', 'auto', 1.0e-8_dp, cfg)
            cfg%solver%device = 'cpu'; cfg%solver%threads = 0
            call run_case(cfg, c, error)
            if (allocated(error)) then
                write (stdout, '("| ",i0," | ",a," |")') cpu_sizes(k), error%message
                deallocate (error); cycle
            end if
            tcpu = fft_pair_seconds(cpu_sizes(k))
            ncpu = omp_threads()
            write (stdout, '("| ",i0," | ",i0," | ",f9.3," | ",i0," | ",f8.3," | ",f6.2," | ",f9.6," | ",es11.4," |")') &
                cpu_sizes(k), ncpu, c%solve_seconds, c%state%operator_applications, 1e3*tcpu, &
                c%solve_seconds/c%state%operator_applications/tcpu, contact_area_fraction(c%state%p), &
                -c%force_pa(1)/cfg%load%mean_pressure_pa
            write (u, '(a,",",i0,",",es14.7,",",i0,",",i0,6(",",es14.7),2(",",es17.10),",",l1,3(",",es14.7))') 'cpu', &
                cpu_sizes(k), c%solve_seconds, c%state%operator_applications, c%state%iterations, 1e3*tcpu, 0.0_dp, &
                c%solve_seconds/c%state%operator_applications/tcpu, 0.0_dp, 0.0_dp, 0.0_dp, &
                contact_area_fraction(c%state%p), -c%force_pa(1)/cfg%load%mean_pressure_pa, c%state%converged, 0.0_dp, &
                0.0_dp, 0.0_dp
            flush (stdout); flush (u)
        end do
        close (u)
    end subroutine bench_gpu

    !> Median time of one cuFFT D2Z + Z2D pair at n^2 (after a warm-up), and the work area it holds
    subroutine cufft_pair(n, minimal, seconds, work_bytes)
        integer, intent(in) :: n
        logical, intent(in) :: minimal
        real(dp), intent(out) :: seconds, work_bytes
        type(transform_t) :: t
        type(error_t), allocatable :: error
        real(dp), allocatable :: x(:, :)
        real(dp) :: ts(7), t0
        integer :: r, i, reps
        call t%on_device(n, n, error, minimal_work=minimal); call check(error)
        allocate (x(n, n))
        call random_number(x(:, 1:min(n, 64)))
        x(:, min(n, 64) + 1:) = 0.5_dp
        call t%x%upload(x)
        deallocate (x)
        call t%forward(); call t%backward_unscaled()
        reps = max(3, min(50, int(2.0e9_dp/real(n, dp)**2)))
        do r = 1, size(ts)
            t0 = device_clock()
            do i = 1, reps
                call t%forward(); call t%backward_unscaled()
            end do
            ts(r) = (device_clock() - t0)/reps
        end do
        call device_check(error, "cuFFT pair"); call check(error)
        seconds = median(ts)
        work_bytes = t%work_bytes
        call t%destroy()
    end subroutine cufft_pair

    integer function omp_threads()
        !$ use omp_lib, only: omp_get_max_threads
        omp_threads = 1
        !$ omp_threads = omp_get_max_threads()
    end function omp_threads

    !> The adhesive solver's cost against the hard wall's on the paper scene (see the program's
    !> header): at each N^2, `rounds` rounds, each solving the adhesive case and then the hard-wall
    !> one on each device of `devices` in turn (interleaved, so that a change of load on the
    !> machine affects all alike). One row per device and grid: FFT pairs, medians of the solve
    !> times (the whole solve: on the device its uploads, plans and downloads), their ratio, the
    !> time per FFT pair spent; before them a line per solve as it ends (the case's whole time beside
    !> the solve's). With VESLIDE_DEVICE_PROFILE=1, each pass's time in the first adhesive solve
    !> at each grid. With 'both', the device's adhesive solution of the first round
    !> against the CPU's: max |dp| / max |p|, the closed cells that differ, the friction's relative
    !> difference.
    subroutine bench_adhesion(devices, rounds, sizes)
        character(len=*), intent(in) :: devices
        integer, intent(in) :: rounds, sizes(:)
        character(len=3), allocatable :: on(:)
        type(config_t) :: cfg(2)
        type(case_t) :: c
        type(error_t), allocatable :: error
        real(dp), allocatable :: t(:, :, :), p(:, :, :), g(:, :, :)
        real(dp) :: fric(2, 2), t0, tol
        integer :: k, r, d, m, pairs(2, 2), its(2, 2)
        logical :: conv(2, 2)
        ! (above the gradient's round-off on the largest grids: docs/validity.md (10))
        tol = 1.0e-10_dp
        call knob_real('VESLIDE_BENCH_TOLERANCE', tol)
        if (.not. (tol > 0.0_dp .and. tol < 1.0_dp)) then
            write (stdout, '(a)') "veslide-bench adhesion: VESLIDE_BENCH_TOLERANCE is a tolerance in (0, 1)"
            error stop 1
        end if
        select case (devices)
        case ('gpu'); on = ['gpu']
        case ('cpu'); on = ['cpu']
        case ('both'); on = ['gpu', 'cpu']
        case default
            write (stdout, '(a)') "veslide-bench adhesion: DEVICES is 'gpu', 'cpu' or 'both', not '"//devices//"'"
            error stop 1
        end select
        if (any(on == 'gpu') .and. (.not. device_enabled .or. device_count() == 0)) then
            write (stdout, '(a)') "veslide-bench adhesion: no device (a GPU build, gpu/build.sh, on a machine with a GPU)"
            error stop 1
        end if
        write (stdout, '(a,es8.1,a,i0,a,i0,a)') "paper scene, tolerance", tol, ", method auto; adhesive: "// &
            "exponential law, w 0.05 J/m^2, range 2 um (inputs/adhesion/sliding.nml); ", rounds, " interleaved rounds, ", &
            omp_threads(), " threads; medians"
        write (stdout, '(a)') "| N | device | FFT pairs, adhesive | FFT pairs, hard wall | pairs ratio |"// &
            " adhesive solve [s] | hard-wall solve [s] | time ratio | adhesive per FFT pair [ms] |"// &
            " hard wall per FFT pair [ms] | iterations (adhesive, hard) | converged | friction (adhesive, hard) |"
        write (stdout, '(a)') "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
        do k = 1, size(sizes)
            call scene(sizes(k), 'visco', 'auto', tol, cfg(2))
            cfg(1) = cfg(2)
            cfg(1)%adhesion%law = 'exponential'; cfg(1)%adhesion%energy_j_m2 = 0.05_dp
            cfg(1)%adhesion%range_m = 2.0e-6_dp
            call complete_config(cfg(1), error); call check(error)
            allocate (t(rounds, 2, size(on)))
            do r = 1, rounds
                do d = 1, size(on)
                    do m = 1, 2
                        cfg(m)%solver%device = on(d); cfg(m)%solver%threads = 0
                        if (r == 1 .and. m == 1) call device_profile()  ! (VESLIDE_DEVICE_PROFILE=1)
                        t0 = now()
                        call run_case(cfg(m), c, error); call check(error)
                        if (r == 1 .and. m == 1) call device_profile()
                        t(r, m, d) = c%solve_seconds
                        write (stdout, '("  round ",i0,", ",i0,"^2 on the ",a,", ",a,": solve ",f0.3," s of ",f0.3, &
                            &" s for the case, ",i0," FFT pairs")') r, sizes(k), on(d), trim(merge('adhesive ', &
                            'hard wall', m == 1)), c%solve_seconds, now() - t0, c%state%operator_applications
                        flush (stdout)
                        pairs(m, d) = c%state%operator_applications; its(m, d) = c%state%iterations
                        conv(m, d) = c%state%converged
                        fric(m, d) = -c%force_pa(1)/cfg(m)%load%mean_pressure_pa
                        if (r == 1 .and. m == 1 .and. size(on) == 2) then
                            if (d == 1) allocate (p(size(c%state%p, 1), size(c%state%p, 2), 2), &
                                                  g(size(c%state%p, 1), size(c%state%p, 2), 2))
                            p(:, :, d) = c%state%p; g(:, :, d) = c%state%g
                        end if
                    end do
                end do
            end do
            do d = 1, size(on)
                write (stdout, '("| ",i0," | ",a," | ",i0," | ",i0," | ",f6.3," | ",f9.3," | ",f9.3," | ",f6.3," | ",&
                    &f9.4," | ",f9.4," | ",i0,", ",i0," | ",l1,", ",l1," | ",es12.5,", ",es12.5," |")') sizes(k), on(d), &
                    pairs(:, d), real(pairs(1, d), dp)/pairs(2, d), median(t(:, 1, d)), median(t(:, 2, d)), &
                    median(t(:, 1, d))/median(t(:, 2, d)), 1e3*median(t(:, 1, d))/pairs(1, d), &
                    1e3*median(t(:, 2, d))/pairs(2, d), its(:, d), conv(:, d), fric(:, d)
            end do
            if (size(on) == 2) then
                write (stdout, '("| ",i0," | device against CPU, adhesive: max |dp|/max |p| ",es9.2,", closed cells that", &
                    &" differ ",i0," of ",i0,", friction ",es9.2," relative |")') sizes(k), &
                    maxval(abs(p(:, :, 1) - p(:, :, 2)))/maxval(abs(p(:, :, 2))), &
                    count((g(:, :, 1) <= 0.0_dp) .neqv. (g(:, :, 2) <= 0.0_dp)), count(g(:, :, 2) <= 0.0_dp), &
                    abs(fric(1, 1) - fric(1, 2))/abs(fric(1, 2))
                deallocate (p, g)
            end if
            deallocate (t)
            flush (stdout)
        end do
    end subroutine bench_adhesion

    !> Westergaard (h0 cos 2 pi x/l, plane strain, p/p* = 0.3) under refinement, per variant
    subroutine bench_kernels()
        real(dp), parameter :: l = 1.0_dp, h0 = 1.0e-3_dp, estar = 1.0e6_dp
        character(len=17), parameter :: names(4) = [character(len=17) :: 'spectral', 'collocation', &
                                                     'collocation-alias', 'galerkin']
        integer, parameter :: variants(4) = [KERNEL_SPECTRAL, KERNEL_COLLOCATION, KERNEL_COLLOCATION_ALIAS, &
                                             KERNEL_GALERKIN]
        type(material_t) :: mat
        type(kernel_t) :: ker
        type(grid_t) :: grid
        type(fft2d_t) :: fft
        type(solver_options_t) :: opts
        type(contact_problem_t) :: problem
        type(contact_state_t) :: s
        type(error_t), allocatable :: error
        real(dp), allocatable :: h(:, :)
        real(dp) :: pstar, p, psi, w_exact, peak_exact, gap_exact
        integer :: v, n
        call new_elastic(mat, estar, 0.0_dp, error); call check(error)
        pstar = pi*estar*h0/l; p = 0.3_dp*pstar; psi = sqrt(p/pstar)
        w_exact = 2.0_dp*asin(psi)/pi
        peak_exact = 2.0_dp*sqrt(p*pstar)
        gap_exact = h0 + 2.0_dp*p*l/(pi*estar)*(log(psi) - 0.5_dp)
        opts%tolerance = 1.0e-12_dp
        write (stdout, '(a)') "| kernel | n | width error [cells] | peak pressure rel. error | mean gap rel. error |"// &
            " alias zones | alias error estimate |"
        write (stdout, '(a)') "|---|---|---|---|---|---|---|"
        do v = 1, 4
            n = 64
            do while (n <= 4096)
                allocate (h(n, 1))
                call new_grid(grid, n, 1, l, l, error); call check(error)
                call cosine_surface(grid, h0, l, 0.0_dp, h)
                call fft%init(n, 1, error, planner='estimate'); call check(error)
                call new_kernel(ker, grid, mat, [0.0_dp, 0.0_dp], variants(v), error, alias_tol=1.0e-10_dp, &
                                alias_max=1024)
                call check(error)
                call new_contact_problem(problem, ker, h, p, error); call check(error)
                call solve_contact(problem, fft, opts, s, error); call check(error)
                write (stdout, '("| ",a," | ",i0," | ",f7.3," | ",es9.2," | ",es9.2," | ",i0," | ",es9.2," |")') &
                    trim(names(v)), n, (contact_area_fraction(s%p) - w_exact)*n, maxval(s%p)/peak_exact - 1, &
                    mean_separation(s%g)/gap_exact - 1, ker%alias_zones, ker%alias_error
                deallocate (h)
                n = 4*n
            end do
        end do
    end subroutine bench_kernels

    !> The paper scene (inputs/default.nml: ratio 11, v tau/L0 = 0.13, 32 kPa, spectrum q0..64 q0, the
    !> same surface on every grid) solved by METHOD at each N^2 to TOL: FFT pairs, iterations, time.
    !> 'elastic' is the same surface on the relaxed solid (E0 = Einf/11). The splitting's knobs
    !> from the environment: VESLIDE_BENCH_MEMORY, _BALANCE_EVERY, _BALANCE_RATIO, _BALANCE_FACTOR.
    !>   veslide-bench scaling elastic|visco METHOD TOL N [N ...]
    subroutine bench_scaling()
        type(config_t) :: cfg
        type(case_t) :: c
        type(error_t), allocatable :: error
        character(len=64) :: kind, method, arg
        real(dp) :: tol
        integer :: k, n
        call get_command_argument(2, kind); call get_command_argument(3, method)
        call get_command_argument(4, arg); read (arg, *) tol
        write (stdout, '(a)') "| solid | method | N | converged | residual | iterations | FFT pairs | solve [s] |"// &
            " area | friction |"
        write (stdout, '(a)') "|---|---|---|---|---|---|---|---|---|---|"
        do k = 5, command_argument_count()
            call get_command_argument(k, arg); read (arg, *) n
            call scene(n, trim(kind), trim(method), tol, cfg)
            call run_case(cfg, c, error); call check(error)
            write (stdout, '("| ",a," | ",a," | ",i0," | ",l1," | ",es8.1," | ",i0," | ",i0," | ",f9.3," | ",f8.5, &
                &" | ",es11.4," |")') trim(kind), c%state%method, n, c%state%converged, c%state%residual, &
                c%state%iterations, c%state%operator_applications, c%solve_seconds, &
                contact_area_fraction(c%state%p), -c%force_pa(1)/cfg%load%mean_pressure_pa
            flush (stdout)
        end do
    end subroutine bench_scaling

    !> The paper scene at n^2 (tolerance 1e-8), one thread: the cost of an iteration of each method
    !> and of each FFT pair it spends, in units of one FFTW r2c + c2r pair timed in the same
    !> process. `rounds` rounds, each timing the pair and then one solve per method (interleaved,
    !> so that a change of load affects all alike); medians over the rounds.
    subroutine bench_iteration(n, rounds)
        integer, intent(in) :: n, rounds
        character(len=*), parameter :: methods(4) = [character(len=4) :: 'bccg', 'pk', 'pdr', 'dr']
        character(len=*), parameter :: solids(4) = [character(len=7) :: 'elastic', 'elastic', 'visco', 'visco']
        type(config_t) :: cfg(4)
        type(case_t) :: c
        type(error_t), allocatable :: error
        real(dp) :: tpair(rounds), tit(rounds, 4), tfft(rounds, 4)
        integer :: its(4), pairs(4), r, m
        do m = 1, 4
            call scene(n, solids(m), methods(m), 1.0e-8_dp, cfg(m))
        end do
        do r = 1, rounds
            tpair(r) = fft_pair_seconds(n)
            do m = 1, 4
                call run_case(cfg(m), c, error); call check(error)
                its(m) = c%state%iterations; pairs(m) = c%state%operator_applications
                tit(r, m) = c%solve_seconds/its(m)
                tfft(r, m) = c%solve_seconds/pairs(m)
            end do
        end do
        write (stdout, '(a,i0,a,i0,a,f8.3,a)') "paper scene at ", n, "^2, tolerance 1e-8, one thread, ", rounds, &
            " interleaved rounds; FFT pair ", 1e3*median(tpair), " ms (median)"
        write (stdout, '(a)') "| method | solid | iterations | FFT pairs | FFT pairs/iteration | time/iteration [ms] |"// &
            " time/iteration [pair-times] | time per FFT pair spent [pair-times] |"
        write (stdout, '(a)') "|---|---|---|---|---|---|---|---|"
        do m = 1, 4
            write (stdout, '("| ",a," | ",a," | ",i0," | ",i0," | ",f6.2," | ",f9.3," | ",f6.2," | ",f6.2," |")') &
                trim(methods(m)), trim(solids(m)), its(m), pairs(m), real(pairs(m), dp)/its(m), 1e3*median(tit(:, m)), &
                median(tit(:, m)/tpair), median(tfft(:, m)/tpair)
        end do
    end subroutine bench_iteration

    !> The cost of the validity measures against the solve they follow: the paper scene at n^2
    !> solved `rounds` times from cold, each solve followed by the measures (veslide_validity's
    !> case_validity; the heights' rms slope comes from the check before the solve), both timed;
    !> medians and their ratio. A study's warm-started solves are faster (0.1-0.9 s at 512^2 on
    !> one thread against a cold 0.5 s), the measures the same.
    subroutine bench_validity(n, rounds)
        integer, intent(in) :: n, rounds
        type(config_t) :: cfg
        type(case_t) :: c
        type(fft2d_t) :: fft
        type(error_t), allocatable :: error
        real(dp) :: ts(rounds), tv(rounds), t0
        integer :: r
        call scene(n, 'visco', 'auto', 1.0e-8_dp, cfg)
        call fft%init(n, n, error, planner='measure'); call check(error)
        do r = 1, rounds
            call run_case(cfg, c, error); call check(error)      ! (the measures are part of it)
            ts(r) = c%solve_seconds
            t0 = now()
            call case_validity(c, fft)
            tv(r) = now() - t0
        end do
        call fft%destroy()
        write (stdout, '(a,i0,a,i0,a)') "validity measures against the solve, paper scene ", n, "^2, ", rounds, &
            " rounds, one thread (medians)"
        write (stdout, '(a,f9.4,a)') "  solve                                     ", median(ts), " s"
        write (stdout, '(a,f9.5,a)') "  validity measures                         ", median(tv), " s"
        write (stdout, '(a,f9.4,a)') "  measures / solve                          ", 100.0_dp*median(tv)/median(ts), " %"
        write (stdout, '(a,i0)') "  warnings                                  ", size(c%warnings)
    end subroutine bench_validity

    !> The cost of the number of Prony terms: the paper scene at n^2 (one thread, tolerance 1e-8)
    !> on a relaxation series of 20 and of 200 terms drawn from one spectrum (a Gaussian over log
    !> rho, rho = 1e-8..1e4 s, Einf = 1e8 Pa, E0 = 1e7 Pa; each term of the long series a tenth of
    !> the short one's density), solved `rounds` times each in turn from cold: the kernel is built
    !> once per case (per speed and temperature in a study), the solve applies it and does not
    !> see the number of terms
    subroutine bench_prony(n, rounds)
        integer, intent(in) :: n, rounds
        integer, parameter :: counts(2) = [20, 200]
        real(dp), parameter :: directions(2) = [0.0_dp, 30.0_dp]
        type(config_t) :: cfg(2)
        type(case_t) :: c
        type(error_t), allocatable :: error
        real(dp) :: tk(rounds, 2), ts(rounds, 2), tc(rounds, 2), t0, x
        integer :: its(2), r, m, j, nt, id
        write (stdout, '(a,i0,a,i0,a)') "Prony terms against the case, paper scene ", n, "^2, ", rounds, &
            " rounds, one thread (medians)"
        do id = 1, size(directions)
            do m = 1, 2
                call scene(n, 'visco', 'auto', 1.0e-8_dp, cfg(m))
                nt = counts(m)
                cfg(m)%motion%direction_deg = directions(id)
                cfg(m)%material%model = 'relaxation'; cfg(m)%material%e0_pa = 1.0e7_dp
                cfg(m)%material%prony_time_s = [(10.0_dp**(-8.0_dp + 12.0_dp*(j - 1)/(nt - 1)), j = 1, nt)]
                cfg(m)%material%prony_coef = [(exp(-0.5_dp*((-8.0_dp + 12.0_dp*(j - 1)/(nt - 1) + 2.0_dp)/ &
                                                            2.0_dp)**2), j = 1, nt)]
                x = sum(cfg(m)%material%prony_coef)
                cfg(m)%material%prony_coef = 9.0e7_dp*cfg(m)%material%prony_coef/x
                call complete_config(cfg(m), error); call check(error)
            end do
            do r = 1, rounds
                do m = 1, 2
                    t0 = now()
                    call run_case(cfg(m), c, error); call check(error)
                    tc(r, m) = now() - t0
                    tk(r, m) = c%kernel_seconds; ts(r, m) = c%solve_seconds; its(m) = c%state%iterations
                end do
            end do
            write (stdout, '(a,f5.1,a)') "  sliding at ", directions(id), " deg from x"
            write (stdout, '(a)') "  terms   kernel [s]   solve [s]   case [s]   iterations"
            do m = 1, 2
                write (stdout, '(i7,3f12.4,i12)') counts(m), median(tk(:, m)), median(ts(:, m)), median(tc(:, m)), &
                    its(m)
            end do
            write (stdout, '(a,f8.2,a)') "  case 200/20 - 1      ", &
                100.0_dp*(median(tc(:, 2))/median(tc(:, 1)) - 1.0_dp), " %"
            write (stdout, '(a,f8.2,a)') "  kernel 200 - 20      ", &
                100.0_dp*(median(tk(:, 2)) - median(tk(:, 1)))/median(tc(:, 1)), " % of the 20-term case"
        end do
    end subroutine bench_prony

    !> The paper scene (see bench_scaling) at n^2 for `solid` ('elastic' or 'visco') and `method`
    subroutine scene(n, solid, method, tol, cfg)
        integer, intent(in) :: n
        character(len=*), intent(in) :: solid, method
        real(dp), intent(in) :: tol
        type(config_t), intent(out) :: cfg
        type(error_t), allocatable :: error
        call default_config(cfg, 'bench')
        cfg%grid%nx = n; cfg%grid%ny = n; cfg%grid%lx_m = 0.01_dp; cfg%grid%ly_m = 0.01_dp
        cfg%surface%k_cut = 64.0_dp
        cfg%material%model = 'one_term'; cfg%material%einf_pa = 1.0e8_dp; cfg%material%ratio = 11.0_dp
        cfg%material%tau_s = 0.01_dp; cfg%material%poisson = 0.5_dp
        cfg%motion%speed_m_s = 0.13_dp
        if (solid == 'elastic') then
            cfg%material%model = 'elastic'; cfg%material%young_pa = 1.0e8_dp/11.0_dp
            cfg%motion%speed_m_s = 0.0_dp
        end if
        cfg%load%mean_pressure_pa = 32.0e3_dp
        cfg%solver%method = method; cfg%solver%tolerance = tol; cfg%solver%threads = 1
        call knob('VESLIDE_BENCH_MEMORY', cfg%solver%anderson_memory)
        call knob('VESLIDE_BENCH_BALANCE_EVERY', cfg%solver%balance_every)
        call knob_real('VESLIDE_BENCH_BALANCE_RATIO', cfg%solver%balance_ratio)
        call knob_real('VESLIDE_BENCH_BALANCE_FACTOR', cfg%solver%balance_factor)
        cfg%output%fields = .false.; cfg%output%file = 'x.h5'
        call complete_config(cfg, error); call check(error)
    end subroutine scene

    !> An integer knob from the environment, when set
    subroutine knob(name, value)
        character(len=*), intent(in) :: name
        integer, intent(inout) :: value
        character(len=32) :: env
        integer :: l, st
        call get_environment_variable(name, env, l, st)
        if (st == 0 .and. l > 0) read (env, *) value
    end subroutine knob

    !> A real knob from the environment, when set
    subroutine knob_real(name, value)
        character(len=*), intent(in) :: name
        real(dp), intent(inout) :: value
        character(len=32) :: env
        integer :: l, st
        call get_environment_variable(name, env, l, st)
        if (st == 0 .and. l > 0) read (env, *) value
    end subroutine knob_real

    !> Every hard case at n^2: converged?, iterations, FFT pairs, time, area, friction
    subroutine bench_hard(n, am, be, br, bf, method, first, last)
        integer, intent(in) :: n, am, be, first, last
        real(dp), intent(in) :: br, bf
        !> method to use ('' or 'default': the configuration's, i.e. 'auto')
        character(len=*), intent(in) :: method
        type(config_t) :: cfg
        type(case_t) :: c
        type(error_t), allocatable :: error
        character(len=:), allocatable :: name
        integer :: k, total
        total = 0
        write (stdout, '(a,i0,a)') "hard cases at ", n, "^2 (tolerance 1e-10)"
        write (stdout, '(a)') "| # | case | method | converged | residual | iterations | FFT pairs | solve [s] |"// &
            " area | friction |"
        write (stdout, '(a)') "|---|---|---|---|---|---|---|---|---|---|"
        do k = first, last
            call hard_case(k, n, cfg, name, error); call check(error)
            if (am >= 0) cfg%solver%anderson_memory = am
            if (be > 0) cfg%solver%balance_every = be
            if (br > 0) cfg%solver%balance_ratio = br
            if (bf > 0) cfg%solver%balance_factor = bf
            if (len(method) > 0 .and. method /= 'default') cfg%solver%method = method
            call run_case(cfg, c, error)
            if (allocated(error)) then
                write (stdout, '("| ",i0," | ",a," | error: ",a," |")') k, name, error%message
                deallocate (error); cycle
            end if
            write (stdout, '("| ",i0," | ",a," | ",a," | ",l1," | ",es8.1," | ",i0," | ",i0," | ",f8.2," | ",f8.5, &
                &" | ",es10.3," |")') k, name, c%state%method, c%state%converged, c%state%residual, &
                c%state%iterations, c%state%operator_applications, c%solve_seconds, &
                contact_area_fraction(c%state%p), 0.0_dp - c%force_pa(1)/cfg%load%mean_pressure_pa
            flush (stdout)
            total = total + c%state%operator_applications
        end do
        write (stdout, '(a,i0)') "total FFT pairs: ", total
    end subroutine bench_hard

    !> A paper-like case (ratio 11, v tau/L0 = 0.13, spectrum q0..32 q0): (1) solver tolerance
    !> against time and error w.r.t. a 1e-13 solution at 256^2; (2) grid size 128^2 .. NMAX^2
    !> against time and the change of area, separation and friction, per kernel variant.
    !> Writes results/bench-accuracy.csv for postproc/plot_benchmarks.py.
    subroutine bench_accuracy(nmax, only)
        integer, intent(in) :: nmax
        character(len=*), intent(in) :: only      !! one kernel variant ('' = all)
        type(config_t) :: cfg
        type(case_t) :: c, ref
        type(error_t), allocatable :: error
        real(dp) :: tols(6), a0, s0, f0, a, s, f, fs, prev(3)
        character(len=17), parameter :: kernels(4) = [character(len=17) :: 'spectral', 'collocation', &
                                                      'collocation-alias', 'galerkin']
        integer :: k, u, n, v
        tols = [1.0e-3_dp, 1.0e-4_dp, 1.0e-6_dp, 1.0e-8_dp, 1.0e-10_dp, 1.0e-12_dp]
        open (newunit=u, file='results/bench-accuracy.csv', status='replace', action='write')
        write (u, '(a)') 'study,kernel,n,tolerance,seconds,fft_pairs,area,separation_m,friction,friction_slope,'// &
            'd_area,d_separation,d_friction'
        call paper_like(256, 'spectral', 1.0e-13_dp, cfg)
        call run_case(cfg, ref, error); call check(error)
        a0 = contact_area_subcell(ref%state%p, ref%state%g, ref%grid); s0 = mean_separation(ref%state%g)
        f0 = -ref%force_pa(1)/cfg%load%mean_pressure_pa
        write (stdout, '(a)') "tolerance study, 256^2, reference tolerance 1e-13"
        write (stdout, '(a)') "| tolerance | solve [s] | FFT pairs | area rel. error | separation rel. error |"// &
            " friction rel. error |"
        write (stdout, '(a)') "|---|---|---|---|---|---|"
        do k = 1, size(tols)
            call paper_like(256, 'spectral', tols(k), cfg)
            call run_case(cfg, c, error); call check(error)
            call measures(c, cfg, a, s, f, fs)
            write (stdout, '("| ",es8.1," | ",f7.3," | ",i0," | ",es9.2," | ",es9.2," | ",es9.2," |")') tols(k), &
                c%solve_seconds, c%state%operator_applications, abs(a/a0 - 1), abs(s/s0 - 1), abs(f/f0 - 1)
            write (u, '(a,",",a,",",i0,",",es10.3,",",f10.4,",",i0,7(",",es16.9))') 'tolerance', 'spectral', 256, &
                tols(k), c%solve_seconds, c%state%operator_applications, a, s, f, fs, abs(a/a0 - 1), abs(s/s0 - 1), &
                abs(f/f0 - 1)
        end do
        write (stdout, '(a)') "grid study, tolerance 1e-10: change from the next coarser grid"
        write (stdout, '(a)') "| kernel | n | solve [s] | kernel build [s] | FFT pairs | area | separation / h_rms |"// &
            " friction | friction <p grad h> | d area | d separation | d friction |"
        write (stdout, '(a)') "|---|---|---|---|---|---|---|---|---|---|---|---|"
        do v = 1, size(kernels)
            if (len(only) > 0 .and. only /= trim(kernels(v))) cycle
            n = 128; prev = 0
            do while (n <= nmax)
                call paper_like(n, kernels(v), 1.0e-10_dp, cfg)
                call run_case(cfg, c, error); call check(error)
                call measures(c, cfg, a, s, f, fs)
                write (stdout, '("| ",a," | ",i0," | ",f8.2," | ",f8.2," | ",i0," | ",f9.6," | ",f9.6," | ",es11.4," | ",&
                    &es11.4," | ",es9.2," | ",es9.2," | ",es9.2," |")') trim(kernels(v)), n, c%solve_seconds, &
                    c%kernel_seconds, c%state%operator_applications, a, s/sqrt(sum(c%h**2)/size(c%h)), f, fs, &
                    merge(abs(a/prev(1) - 1), 0.0_dp, n > 128), merge(abs(s/prev(2) - 1), 0.0_dp, n > 128), &
                    merge(abs(f/prev(3) - 1), 0.0_dp, n > 128)
                write (u, '(a,",",a,",",i0,",",es10.3,",",f10.4,",",i0,7(",",es16.9))') 'grid', trim(kernels(v)), n, &
                    1.0e-10_dp, c%solve_seconds, c%state%operator_applications, a, s, f, fs, &
                    merge(abs(a/prev(1) - 1), 0.0_dp, n > 128), merge(abs(s/prev(2) - 1), 0.0_dp, n > 128), &
                    merge(abs(f/prev(3) - 1), 0.0_dp, n > 128)
                prev = [a, s, f]
                n = 2*n
            end do
        end do
        close (u)
    end subroutine bench_accuracy

    subroutine measures(c, cfg, a, s, f, fs)
        type(case_t), intent(in) :: c
        type(config_t), intent(in) :: cfg
        real(dp), intent(out) :: a, s, f, fs
        a = contact_area_subcell(c%state%p, c%state%g, c%grid); s = mean_separation(c%state%g)
        f = -c%force_pa(1)/cfg%load%mean_pressure_pa; fs = -c%slope_force_pa(1)/cfg%load%mean_pressure_pa
    end subroutine measures

    subroutine paper_like(n, kernel, tol, cfg)
        integer, intent(in) :: n
        character(len=*), intent(in) :: kernel
        real(dp), intent(in) :: tol
        type(config_t), intent(out) :: cfg
        type(error_t), allocatable :: error
        call default_config(cfg, 'bench')
        cfg%grid%nx = n; cfg%grid%ny = n; cfg%grid%lx_m = 0.01_dp; cfg%grid%ly_m = 0.01_dp; cfg%surface%k_cut = 32.0_dp
        cfg%material%model = 'one_term'; cfg%material%einf_pa = 1.0e8_dp; cfg%material%ratio = 11.0_dp
        cfg%material%tau_s = 0.01_dp
        cfg%motion%speed_m_s = 0.13_dp; cfg%solver%tolerance = tol; cfg%solver%kernel = kernel
        cfg%solver%alias_tol = 1.0e-6_dp
        cfg%solver%threads = 1; cfg%output%fields = .false.; cfg%output%file = 'x.h5'
        call complete_config(cfg, error); call check(error)
    end subroutine paper_like

end program veslide_bench
