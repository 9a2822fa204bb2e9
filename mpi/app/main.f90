!> veslide-batch FILE.nml [--output PATH] [--overwrite] [--quiet]: FILE.nml on every MPI rank at once
!> (--output PATH: the result file instead of &output file, as for veslide).
!> A single case (no &sweep list): one grid distributed over the ranks (FFTW's MPI transforms,
!> rows of every field per rank), solved together and written collectively (parallel HDF5) into
!> the file a serial run writes. A study: rank r runs the speed chains (seed, temperature,
!> eccentricity, angle, pressure) whose index is r modulo the
!> number of ranks, each warm-started along speed as in a serial study, into a rank file next to
!> the output; when every rank has finished, rank 0 joins the rank files into the study file
!> (veslide_study's merge: the same /summary and /ensemble as a serial run), publishes it as a
!> serial run does, and removes the rank files.
program veslide_batch
    use, intrinsic :: iso_fortran_env, only: stderr => error_unit, stdout => output_unit
    use mpi_f08
    use veslide_error, only: error_t, exit_status
    use veslide_config, only: config_t, read_config
    use veslide_output, only: prepare_output, release_output, commit_output, discard_output
    use veslide_study, only: run_study, merge_study_parts, study_progress_t, plan_study_transforms, JUMP_IN, JUMP_OUT
    use veslide_device, only: device_enabled, device_count, device_select
    use veslide_case, only: case_t, run_case
    use veslide_case_file, only: write_case
    use veslide_quantities, only: results_t, case_results
    use veslide_summary, only: header_lines, summary_lines, summary_width, write_warnings
    use veslide_strings, only: str
    use veslide_case_data, only: case_spec_t
    use veslide_case_spec, only: case_spec_of
    use veslide_solver_options, only: solver_progress_t, progress_line
    use veslide_system, only: ignore_file_size_signal
    use veslide_version, only: version_string
    implicit none
    character(len=*), parameter :: usage = &
        "usage: mpirun -n N veslide-batch FILE.nml [--output PATH] [--overwrite] [--quiet]"
    type(config_t) :: cfg
    type(error_t), allocatable :: error
    character(len=:), allocatable :: input, out, tmp, mine, arg, output
    character(len=:), allocatable :: parts(:)
    integer :: rank, nranks, nfail, total, k, n, status, failed, lock
    logical :: overwrite, quiet, output_given

    call MPI_Init()
    call MPI_Comm_rank(MPI_COMM_WORLD, rank)
    call MPI_Comm_size(MPI_COMM_WORLD, nranks)
    overwrite = .false.; quiet = .false.; output_given = .false.; output = ''
    allocate (character(len=0) :: input)
    ! the options of veslide that apply here, with its meanings and its messages
    k = 1
    do while (k <= command_argument_count())
        arg = argument(k)
        select case (arg)
        case ('-h', '--help')
            call finish(usage//new_line('a')//"  runs the case (a grid distributed over the ranks) or the &sweep"// &
                        " study FILE.nml describes;"//new_line('a')//"  --output PATH: the result file instead of"// &
                        " &output file (a relative PATH is the caller's)")
        case ('--version')
            call finish('veslide-batch '//version_string())
        case ('-o', '--output')
            k = k + 1
            if (k > command_argument_count()) call die("veslide-batch: "//arg//" needs a file name")
            output = argument(k); output_given = .true.
            if (len(output) == 0) call die("veslide-batch: "//arg//" needs a file name, got ''")
        case ('--overwrite')
            overwrite = .true.
        case ('-q', '--quiet')
            quiet = .true.
        case default
            if (index(arg, '-') == 1) call die("veslide-batch: unknown option '"//arg//"' ("//usage//")")
            if (len(input) > 0) call die("veslide-batch: only one input file, got '"//input//"' and '"//arg//"'")
            input = arg
        end select
        k = k + 1
    end do
    if (len(input) == 0) call die(usage)
    call ignore_file_size_signal()        ! a write past `ulimit -f` fails like a full disk, not fatally
    call read_config(input, cfg, error, surface_statistics=rank == 0)   ! a height file read whole once
    ! (a study's ranks each read the whole height file anyway, and each writes its cases' warnings)
    if (.not. allocated(error) .and. rank /= 0 .and. cfg%sweep%is_study()) call read_config(input, cfg, error)
    if (allocated(error)) call die(error%message, exit_status(error))
    ! warnings are part of the result: printed whatever --quiet says
    if (rank == 0) call write_warnings(stderr, cfg%warnings, cfg%path, with_input=.true.)
    if (output_given) cfg%output%file = output
    out = cfg%output%file
    status = 0
    if (rank == 0) then
        call prepare_output(out, overwrite .or. cfg%output%overwrite, tmp, lock, error)
        if (allocated(error)) status = exit_status(error)
    end if
    call agree(status); if (status /= 0) call die(error_text(), status)
    if (.not. cfg%sweep%is_study()) call distributed_case()
    ! rank files: OUT.rankNNNN-of-RRRR.part (the count in the name keeps runs of another size apart)
    allocate (character(len=len(out) + 24) :: parts(nranks))
    do k = 1, nranks
        write (parts(k), '(a,".rank",i4.4,"-of-",i4.4,".part")') out, k - 1, nranks
    end do
    mine = trim(parts(rank + 1))
    ! with a device backend, each rank its own GPU: rank modulo the number this process sees
    if (device_enabled) then
        if (device_count() > 0) call device_select(modulo(rank, device_count()), error)
        if (allocated(error)) then
            write (stderr, '(a,i0,a)') "veslide-batch: rank ", rank, ": "//error%message
            deallocate (error)
        end if
    end if
    ! the study's FFT plans measured once, by rank 0, before any rank plans its own: every rank then
    ! plans from that wisdom, as every later run does (an error is run_study's to report)
    if (rank == 0) call plan_study_transforms(cfg, error)
    if (allocated(error)) deallocate (error)
    call MPI_Barrier(MPI_COMM_WORLD)
    ! (each rank solves whole cases; the ranks of one machine share its free memory)
    call run_study(cfg, mine, nfail, error, progress=print_progress, part=[rank, nranks], &
                   node_ranks=ranks_on_this_machine())      ! (quiet: its warnings only)
    ! the exit status: the largest of the ranks' (1 input, 3 I/O, 4 numerical; 0 none failed)
    failed = 0
    if (allocated(error)) failed = exit_status(error)
    if (allocated(error)) write (stderr, '(a,i0,a)') "veslide-batch: rank ", rank, ": "//error%message
    call MPI_Allreduce(MPI_IN_PLACE, failed, 1, MPI_INTEGER, MPI_MAX, MPI_COMM_WORLD)
    call MPI_Reduce(nfail, total, 1, MPI_INTEGER, MPI_SUM, 0, MPI_COMM_WORLD)
    if (failed > 0) then
        call discard_output(mine)
        if (rank == 0) then
            call discard_output(tmp); call release_output(lock, out)
        end if
        call MPI_Finalize(); stop failed, quiet=.true.
    end if
    if (rank == 0) then
        call merge_study_parts(cfg, tmp, parts, error)
        if (.not. allocated(error)) call commit_output(tmp, out, overwrite .or. cfg%output%overwrite, error)
        if (allocated(error)) then
            write (stderr, '(a)') error%message
            call discard_output(tmp); status = exit_status(error)
            call release_output(lock, out)
        else
            call release_output(lock, out)
            do k = 1, nranks
                call discard_output(trim(parts(k)))
            end do
            if (.not. quiet) write (stdout, '(a,i0,a)') "veslide-batch: study of ", nranks, " ranks written to "//out
            if (total > 0) write (stderr, '(a,i0,a)') "veslide-batch: NOT CONVERGED in ", total, &
                " case(s) (see /summary converged)"
        end if
    end if
    call MPI_Bcast(status, 1, MPI_INTEGER, 0, MPI_COMM_WORLD)
    call MPI_Finalize()
    if (status /= 0) stop status, quiet=.true.
    if (total > 0 .and. rank == 0) stop 2, quiet=.true.   ! a controlled exit: the message is printed above

contains

    !> One case on a grid shared by all ranks; the ranks of one machine share its free memory
    subroutine distributed_case()
        type(case_t) :: c
        type(results_t) :: r
        character(len=summary_width), allocatable :: lines(:)
        integer :: node_ranks, i, nlen
        nlen = 0; if (rank == 0) nlen = len(tmp)
        call MPI_Bcast(nlen, 1, MPI_INTEGER, 0, MPI_COMM_WORLD)
        if (rank /= 0) allocate (character(len=nlen) :: tmp)
        call MPI_Bcast(tmp, nlen, MPI_CHARACTER, 0, MPI_COMM_WORLD)
        node_ranks = ranks_on_this_machine()
        if (rank == 0 .and. .not. quiet) then
            block
                type(case_spec_t) :: spec
                allocate (lines(0))
                call case_spec_of(cfg, spec, error)
                if (.not. allocated(error)) lines = header_lines(spec, out)
                if (allocated(error)) deallocate (error)      ! (run_case reports it to every rank)
                do i = 1, size(lines)
                    write (stdout, '(a)') trim(lines(i))
                end do
                flush (stdout)
            end block
        end if
        if (rank == 0 .and. .not. quiet) then      ! rank 0 reports the whole grid's state
            call run_case(cfg, c, error, comm=MPI_COMM_WORLD%MPI_VAL, node_ranks=node_ranks, &
                          progress=print_solver_progress)
        else
            call run_case(cfg, c, error, comm=MPI_COMM_WORLD%MPI_VAL, node_ranks=node_ranks)
        end if
        if (.not. allocated(error)) call write_case(tmp, c, error)
        if (allocated(error)) then          ! every rank holds the same verdict
            if (rank == 0) then
                write (stderr, '(a)') error%message
                call discard_output(tmp); call release_output(lock, out)
            end if
            status = exit_status(error)
            call MPI_Finalize(); stop status, quiet=.true.
        end if
        call case_results(c, r)        ! (collective)
        if (rank == 0) then
            call commit_output(tmp, out, overwrite .or. cfg%output%overwrite, error)
            call release_output(lock, out)
            if (allocated(error)) then
                write (stderr, '(a)') error%message; status = exit_status(error)
            else if (.not. quiet) then
                lines = summary_lines(c, r)
                do i = 1, size(lines)
                    write (stdout, '(a)') trim(lines(i))
                end do
            end if
            call write_warnings(stderr, c%warnings, cfg%path, with_input=.false.)
            if (status == 0 .and. .not. c%state%converged) write (stderr, '(a,es9.2,a,es9.2,a,i0,a)') &
                "veslide-batch: NOT CONVERGED: residual ", c%state%residual, " > tolerance ", cfg%solver%tolerance, &
                " after ", c%state%iterations, " iterations (result written with /scalars/converged = 0)"
        end if
        call MPI_Bcast(status, 1, MPI_INTEGER, 0, MPI_COMM_WORLD)
        call MPI_Finalize()
        if (status /= 0) stop status, quiet=.true.
        if (.not. c%state%converged) stop 2, quiet=.true.
        stop
    end subroutine distributed_case

    function argument(i) result(a)
        integer, intent(in) :: i
        character(len=:), allocatable :: a
        call get_command_argument(i, length=n)
        allocate (character(len=n) :: a)
        call get_command_argument(i, a)
    end function argument

    !> --help, --version: the text from rank 0, exit status 0
    subroutine finish(text)
        character(len=*), intent(in) :: text
        if (rank == 0) write (stdout, '(a)') text
        call MPI_Finalize()
        stop
    end subroutine finish

    !> A line every few seconds of a long solve (the residual and counts are global)
    subroutine print_solver_progress(info)
        type(solver_progress_t), intent(in) :: info
        write (stdout, '(a)') progress_line(info)
        flush (stdout)
    end subroutine print_solver_progress

    !> Every rank learns whether rank 0 failed
    !> How many of the ranks run on this machine (they share its free memory)
    integer function ranks_on_this_machine() result(n)
        type(MPI_Comm) :: node
        call MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, node)
        call MPI_Comm_size(node, n)
        call MPI_Comm_free(node)
    end function ranks_on_this_machine

    subroutine agree(flag)
        integer, intent(inout) :: flag
        call MPI_Bcast(flag, 1, MPI_INTEGER, 0, MPI_COMM_WORLD)
    end subroutine agree

    function error_text() result(t)
        character(len=:), allocatable :: t
        t = "veslide-batch: the output cannot be written"
        if (allocated(error)) t = error%message
    end function error_text

    !> A refusal before any work: one line (from rank 0), no MPI_Abort noise
    subroutine die(message, status)
        character(len=*), intent(in) :: message
        integer, intent(in), optional :: status      !! the exit status (default 1: a bad command line)
        integer :: code
        code = 1; if (present(status)) code = status
        if (rank == 0) write (stderr, '(a)') message
        call MPI_Finalize()
        stop code, quiet=.true.
    end subroutine die

    subroutine print_progress(info)
        type(study_progress_t), intent(in) :: info
        if (info%case_number > 0 .and. allocated(info%warnings)) &
            call write_warnings(stderr, info%warnings, cfg%path//": case "//str(info%case_number), with_input=.false.)
        if (quiet) return
        if (info%case_number == 0) then
            write (stdout, '("rank ",i0,"/",i0,": resumed from its part file: ",i0," of ",i0, &
                &" cases kept, ",i0," to run")') rank, nranks, info%resumed, info%total, info%total - info%resumed
            flush (stdout)
            return
        end if
        write (stdout, '("rank ",i0,"/",i0,": case ",i0," (",i0,"/",i0," of this rank): v ",es9.3," m/s, area ",f8.5, &
            &", f ",es10.3,", ",i0," FFT pairs",a,", ",f7.2," s; rank done in ~",f8.1," s")') rank, nranks, &
            info%case_number, info%done, info%total, info%speed_m_s, info%contact_area_fraction, &
            info%friction_coefficient, info%operator_applications, &
            trim(merge('               ', ', NOT CONVERGED', info%converged))//path_note(info), info%case_s, &
            info%elapsed_s/(info%done - info%resumed)*(info%total - info%done)
        flush (stdout)
    end subroutine print_progress

    !> A load path's case: its place on the path and a jump since the previous case (as veslide's)
    function path_note(info) result(note)
        type(study_progress_t), intent(in) :: info
        character(len=:), allocatable :: note
        note = ''
        if (info%path_step == 0) return
        note = ", step "//str(info%path_step)
        if (info%path_jump == JUMP_IN) note = note//", JUMP-IN"
        if (info%path_jump == JUMP_OUT) note = note//", JUMP-OUT"
    end function path_note

end program veslide_batch
