!> veslide FILE.nml [--output PATH] [--overwrite] [--quiet] [--device auto|cpu|gpu]
!> veslide --memory FILE.nml [--processes R] [--device auto|cpu|gpu]
!> Runs the case or the study a namelist describes and writes its HDF5 result; see README.md.
program veslide_main
    use, intrinsic :: iso_fortran_env, only: stderr => error_unit, stdout => output_unit
    use veslide_error, only: error_t, exit_status
    use veslide_config, only: config_t, read_config
    use veslide_output, only: prepare_output, release_output, commit_output, discard_output
    use veslide_quantities, only: results_t, case_results
    use veslide_case_data, only: case_spec_t
    use veslide_case_spec, only: case_spec_of
    use veslide_case, only: case_t, run_case
    use veslide_case_file, only: write_case
    use veslide_summary, only: header_lines, summary_lines, summary_width, write_warnings
    use veslide_memory, only: format_gib, device_estimate_bytes, case_memory
    use veslide_system, only: available_memory_bytes
    use veslide_kinds, only: i8, dp
    use veslide_study, only: run_study, study_progress_t, plan_study, study_plan_t, JUMP_IN, JUMP_OUT
    use veslide_solver_options, only: solver_progress_t, progress_line
    use veslide_version, only: version_string
    use veslide_strings, only: str
    use veslide_system, only: ignore_file_size_signal, exit_now, prefer_passive_wait, catch_termination, &
                              defer_termination, allow_termination
    use veslide_solver_options, only: device_choice_id, solver_method_id
    use veslide_solver_table, only: runs_on_device
    use veslide_solver, only: gpu_visible
    use veslide_device, only: device_enabled, device_info_t, device_info, device_memory
    implicit none
    type(config_t) :: cfg
    type(case_spec_t) :: spec
    type(case_t) :: c
    type(error_t), allocatable :: error
    character(len=:), allocatable :: input, output, tmp, arg, device
    logical :: overwrite, quiet, output_given, memory_only
    integer :: i, n, lock, processes

    call prefer_passive_wait()            ! threads that wait sleep (docs/solver-scaling.md)
    overwrite = .false.; quiet = .false.; lock = -1; memory_only = .false.; processes = 1
    call ignore_file_size_signal()        ! a write past `ulimit -f` fails like a full disk, not fatally
    call catch_termination()              ! a stop (SIGTERM, SIGINT, SIGHUP) waits for a study's write
    output = ''; device = ''
    allocate (character(len=0) :: input)
    output_given = .false.
    i = 1
    do while (i <= command_argument_count())
        arg = argument(i)
        select case (arg)
        case ('-h', '--help')
            call usage(); stop
        case ('--version')
            write (stdout, '(a)') 'veslide '//version_string(); stop
        case ('-o', '--output')
            i = i + 1
            if (i > command_argument_count()) call die("veslide: "//arg//" needs a file name")
            output = argument(i); output_given = .true.
            if (len(output) == 0) call die("veslide: "//arg//" needs a file name, got ''")
        case ('--overwrite')
            overwrite = .true.
        case ('--memory')
            memory_only = .true.
        case ('--processes')
            i = i + 1
            if (i > command_argument_count()) call die("veslide: --processes needs a number of processes")
            arg = argument(i)
            read (arg, *, iostat=n) processes
            if (n /= 0 .or. processes < 1) call die("veslide: --processes needs a whole number >= 1, got '"// &
                                                   arg//"'")
        case ('--device')
            i = i + 1
            if (i > command_argument_count()) call die("veslide: --device needs one of 'auto', 'cpu', 'gpu'")
            device = argument(i)
            if (device_choice_id(device) == 0) call die("veslide: --device '"//device//"' is not one of 'auto',"// &
                                                        " 'cpu', 'gpu'")
        case ('-q', '--quiet')
            quiet = .true.
        case default
            if (arg(1:1) == '-') call die("veslide: unknown option '"//arg//"' (see veslide --help)")
            if (len(input) > 0) call die("veslide: only one input file, got '"//input//"' and '"//arg//"'")
            input = arg
        end select
        i = i + 1
    end do
    if (len(input) == 0) then
        call usage(); call die("veslide: no input file")
    end if

    ! the input, and the options that override it: the configuration is not written after this
    call read_config(input, cfg, error)
    if (allocated(error)) call fail(error)
    if (len(device) > 0) cfg%solver%device = device     ! --device overrides &solver device
    if (output_given) cfg%output%file = output
    if (overwrite) cfg%output%overwrite = .true.
    call case_spec_of(cfg, spec, error)
    if (allocated(error)) call fail(error)
    if (memory_only) call print_memory()
    ! warnings are part of the result: printed whatever --quiet says (and written to the file)
    call write_warnings(stderr, cfg%warnings, cfg%path, with_input=.true.)
    ! a GPU build where no GPU is visible runs on the CPU, and says so once
    if (.not. quiet .and. device_enabled .and. cfg%solver%device == 'auto' .and. .not. gpu_visible()) &
        write (stderr, '(a)') "veslide: this build has GPU support but no GPU is visible here: solving on the CPU"
    call prepare_output(cfg%output%file, cfg%output%overwrite, tmp, lock, error)
    if (allocated(error)) call fail(error)
    if (.not. quiet .and. .not. cfg%sweep%is_study()) call header()

    if (cfg%sweep%is_study()) then
        block
            integer :: nfail
            logical :: resuming
            ! a part file left by a killed run of this study is resumed, and kept if this run fails
            inquire (file=tmp, exist=resuming)
            ! (a stop ends the study during a solve, or after the write under way: the part file
            ! is never left half-written)
            call defer_termination()
            call run_study(cfg, tmp, nfail, error, progress=print_progress)   ! (quiet: its warnings only)
            if (allocated(error)) then
                if (.not. resuming) call discard_output(tmp)
                call fail(error)
            end if
            call commit_output(tmp, cfg%output%file, cfg%output%overwrite, error)
            call allow_termination()
            if (allocated(error)) call fail(error)
            call release_output(lock, cfg%output%file)
            if (.not. quiet) write (stdout, '(a)') "veslide: study written to "//cfg%output%file
            if (nfail > 0) then
                write (stderr, '(a,i0,a)') "veslide: NOT CONVERGED in ", nfail, &
                    " case(s) (see /summary converged)"
                stop 2, quiet=.true.   ! a controlled exit: the message is printed above
            end if
            stop
        end block
    end if
    if (quiet) then
        call run_case(spec, c, error)
    else
        call run_case(spec, c, error, progress=print_solver_progress)
    end if
    if (allocated(error)) then
        call discard_output(tmp); call fail(error)
    end if
    call write_case(tmp, c, error)
    if (allocated(error)) then
        call discard_output(tmp)
        error%message = "veslide: &output file '"//cfg%output%file//"' could not be written (disk full,"// &
                        " file-size limit or I/O error; nothing was published): "//error%message
        call fail(error)
    end if
    call commit_output(tmp, cfg%output%file, cfg%output%overwrite, error)
    if (allocated(error)) call fail(error)
    call release_output(lock, cfg%output%file)

    if (.not. quiet) call summary()
    call write_warnings(stderr, c%warnings, cfg%path, with_input=.false.)
    if (.not. c%state%converged) then
        write (stderr, '(a,es9.2,a,es9.2,a,i0,a)') "veslide: NOT CONVERGED: residual ", c%state%residual, &
            " > tolerance ", cfg%solver%tolerance, " after ", c%state%iterations, &
            " iterations (result written with /scalars/converged = 0)"
        stop 2, quiet=.true.   ! a controlled exit: the message is printed above
    end if

contains

    function argument(k) result(a)
        integer, intent(in) :: k
        character(len=:), allocatable :: a
        call get_command_argument(k, length=n)
        allocate (character(len=n) :: a)
        call get_command_argument(k, a)
    end function argument

    !> One line on stderr and exit status `status` (default 1: a bad command line); no backtrace,
    !> library exit handlers skipped, since after a failed write HDF5's own may crash
    subroutine die(message, status)
        character(len=*), intent(in) :: message
        integer, intent(in), optional :: status
        write (stderr, '(a)') message
        if (allocated(cfg%output%file)) call release_output(lock, cfg%output%file)
        if (present(status)) call exit_now(status)
        call exit_now(1)
    end subroutine die

    !> Stop on `error`: its message, and the exit status of its category (1 input, 3 I/O, 4 numerical)
    subroutine fail(error)
        type(error_t), intent(in) :: error
        call die(error%message, exit_status(error))
    end subroutine fail

    !> --memory: the estimate of the run's peak memory, per process on `processes` processes (the
    !> memory a job must request; refused runs are refused on this estimate), then stop
    subroutine print_memory()
        integer(i8) :: estimate, available, on_device, roomy
        character(len=:), allocatable :: room_note
        type(study_plan_t) :: plan
        type(device_info_t) :: info
        real(dp) :: free_b, total_b
        if (cfg%sweep%is_study()) then        ! each rank of an MPI study solves whole cases
            call plan_study(cfg, plan)
            call case_memory(spec, estimate, device_estimate=on_device, speeds=plan%speeds)
        else
            call case_memory(spec, estimate, processes, on_device)
        end if
        available = available_memory_bytes()
        if (processes > 1 .and. cfg%sweep%is_study()) then
            write (stdout, '(a,i0,a,i0,a,i0,a)') cfg%path//": grid ", cfg%grid%nx, " x ", cfg%grid%ny, &
                ", a study on ", processes, " processes (MPI, mpi/run.sh; each solves whole cases): about "// &
                format_gib(estimate)//" per process"
        else if (processes > 1) then
            write (stdout, '(a,i0,a,i0,a,i0,a)') cfg%path//": grid ", cfg%grid%nx, " x ", cfg%grid%ny, " on ", &
                processes, " processes (MPI, mpi/run.sh): about "//format_gib(estimate)//" per process"
        else
            write (stdout, '(a,i0,a,i0,a)') cfg%path//": grid ", cfg%grid%nx, " x ", cfg%grid%ny, &
                ": about "//format_gib(estimate)//" in one process"
        end if
        if (available >= 0) write (stdout, '(a)') "available to this process here and now: "//format_gib(available)
        if (on_device > 0) then
            ! what the solve holds where the device has room for all it takes (pdr: cuFFT's own
            ! work area), when that is more than it needs
            if (cfg%sweep%is_study()) then
                roomy = device_estimate_bytes(spec, speeds=plan%speeds, room=.true.)
            else
                roomy = device_estimate_bytes(spec, room=.true.)
            end if
            room_note = ""
            if (roomy > on_device) room_note = " at least, "//format_gib(roomy)//" where it has room for all it"// &
                " takes (cuFFT's own work area)"
            write (stdout, '(a)') "on the device (&solver device = '"//cfg%solver%device//"'): about "// &
                format_gib(on_device)//" of device memory"//room_note
            call device_info(info, error)
            if (.not. allocated(error)) call device_memory(free_b, total_b, error)
            if (.not. allocated(error) .and. free_b >= 0) write (stdout, '(a)') "free on the "//info%name// &
                " here and now: "//format_gib(int(free_b, i8))//" of "//format_gib(int(total_b, i8))
        else if (runs_on_device(solver_method_id(cfg%solver%method)) .and. processes == 1) then
            if (cfg%sweep%is_study()) then
                on_device = device_estimate_bytes(spec, speeds=plan%speeds)
            else
                on_device = device_estimate_bytes(spec)
            end if
            write (stdout, '(a)') "solved on a GPU (&solver device = 'gpu', gpu/build.sh) it would need about "// &
                format_gib(on_device)//" of device memory"
        end if
        stop
    end subroutine print_memory

    subroutine usage()
        write (stdout, '(a)') "usage: veslide FILE.nml [--output PATH] [--overwrite] [--quiet] [--device auto|cpu|gpu]", &
            "       veslide --memory FILE.nml [--processes R] [--device D]   (the memory a run needs, per process,", &
            "                                                             and on the device)", &
            "  --device: where the solve runs (overrides &solver device): 'auto' a GPU when this build has", &
            "  GPU support and one is visible, 'cpu', or 'gpu' (refused when there is none).", &
            "  Solves the steady sliding contact (or the &sweep study) the namelist describes and writes", &
            "  an HDF5 file (default &output file). Exit status: 0 converged, 1 bad input, 2 solved but not", &
            "  converged (the file is written, /scalars/converged = 0), 3 a file could not be read or written,", &
            "  4 the numbers broke down (a discrete kernel that is not positive definite, an overflow)."
    end subroutine usage

    !> One line per finished case of a study, with the time left at the mean pace so far (not
    !> with --quiet), and the case's warnings (always)
    subroutine print_progress(info)
        type(study_progress_t), intent(in) :: info
        if (info%case_number > 0 .and. allocated(info%warnings)) &
            call write_warnings(stderr, info%warnings, cfg%path//": case "//str(info%case_number), with_input=.false.)
        if (quiet) return
        if (info%case_number == 0) then
            write (stdout, '("study resumed from its part file: ",i0," of ",i0," cases kept, ",i0," to run")') &
                info%resumed, info%total, info%total - info%resumed
            flush (stdout)
            return
        end if
        write (stdout, '("case ",i0,"/",i0,": seed ",i0,", eps ",f5.3,", alpha ",f6.1," deg, p ",es10.3, &
            &" Pa, v ",es9.3," m/s: area ",f8.5,", f ",es10.3,", ",i0," FFT pairs",a,", ",f7.2," s; elapsed ",f8.1, &
            &" s, left ~",f8.1," s")') info%done, info%total, info%seed, info%eccentricity, info%alpha_deg, &
            info%pressure_pa, info%speed_m_s, info%contact_area_fraction, info%friction_coefficient, &
            info%operator_applications, trim(merge('               ', ', NOT CONVERGED', info%converged))// &
            path_note(info), info%case_s, info%elapsed_s, &
            info%elapsed_s/(info%done - info%resumed)*(info%total - info%done)
        flush (stdout)
    end subroutine print_progress

    !> A load path's case: its place on the path, the approach given (approach control; p is then
    !> the load carried), a jump since the previous case, and the patches made or lost since then
    !> that the path held the other way at the same load before (bistable)
    function path_note(info) result(note)
        type(study_progress_t), intent(in) :: info
        character(len=:), allocatable :: note
        character(len=16) :: buf
        note = ''
        if (info%path_step == 0) return
        note = ", step "//str(info%path_step)
        if (info%approach_m /= huge(1.0_dp)) then
            write (buf, '(es10.3)') info%approach_m
            note = note//", approach "//trim(adjustl(buf))//" m"
        end if
        if (info%path_jump == JUMP_IN) note = note//", JUMP-IN"
        if (info%path_jump == JUMP_OUT) note = note//", JUMP-OUT"
        if (info%path_bistable > 0) note = note//", "//str(info%path_bistable)// &
                                           trim(merge(" BISTABLE PATCH  ", " BISTABLE PATCHES", info%path_bistable == 1))
    end function path_note

    !> A line every few seconds of a long solve
    subroutine print_solver_progress(info)
        type(solver_progress_t), intent(in) :: info
        write (stdout, '(a)') progress_line(info)
        flush (stdout)
    end subroutine print_solver_progress

    !> The header of a single case, before its solve
    subroutine header()
        character(len=summary_width), allocatable :: lines(:)
        lines = header_lines(spec, cfg%output%file)
        do i = 1, size(lines)
            write (stdout, '(a)') trim(lines(i))
        end do
        flush (stdout)
    end subroutine header

    !> The run summary, read from the case's results list
    subroutine summary()
        type(results_t) :: r
        character(len=summary_width), allocatable :: lines(:)
        call case_results(c, r)
        lines = summary_lines(c, r)
        do i = 1, size(lines)
            write (stdout, '(a)') trim(lines(i))
        end do
    end subroutine summary

end program veslide_main
