!> veslide-batch FILE.nml [--overwrite]: the study of FILE.nml on every MPI rank at once.
!> Rank r runs the speed chains (seed, eccentricity, angle, pressure) whose index is r modulo
!> the number of ranks, each warm-started along speed as in a serial study, and writes
!> OUT.rankNNNN.h5 (OUT = &output file without .h5) with global case numbers;
!> postproc/merge_ranks.py joins the parts into one study file with /summary and /ensemble.
program veslide_batch
    use, intrinsic :: iso_fortran_env, only: stderr => error_unit, stdout => output_unit
    use mpi_f08
    use veslide_error, only: error_t
    use veslide_config, only: config_t, read_config
    use veslide_run, only: prepare_output, commit_output, discard_output
    use veslide_sweep, only: run_sweep
    implicit none
    type(config_t) :: cfg
    type(error_t), allocatable :: error
    character(len=:), allocatable :: input, base, out, tmp
    character(len=512) :: arg
    character(len=16) :: suffix
    integer :: rank, nranks, nfail, total, k, n
    logical :: overwrite

    call MPI_Init()
    call MPI_Comm_rank(MPI_COMM_WORLD, rank)
    call MPI_Comm_size(MPI_COMM_WORLD, nranks)
    overwrite = .false.; allocate (character(len=0) :: input)
    do k = 1, command_argument_count()
        call get_command_argument(k, arg, n)
        if (trim(arg) == '--overwrite') then
            overwrite = .true.
        else
            input = trim(arg)
        end if
    end do
    if (len(input) == 0) call die("usage: mpirun -n N veslide-batch FILE.nml [--overwrite]")
    call read_config(input, cfg, error)
    if (allocated(error)) call die(error%message)
    if (.not. cfg%is_sweep) call die("veslide-batch: "//input//" has no &sweep list; run it with veslide")
    base = cfg%output_file
    if (len(base) > 3) then
        if (base(len(base) - 2:) == '.h5') base = base(:len(base) - 3)
    end if
    write (suffix, '(".rank",i4.4,".h5")') rank
    out = base//trim(suffix)
    call prepare_output(out, overwrite .or. cfg%overwrite, tmp, error)
    if (allocated(error)) call die(error%message)
    call run_sweep(cfg, tmp, nfail, error, quiet=rank /= 0, part=[rank, nranks])
    if (allocated(error)) then
        call discard_output(tmp); call die(error%message)
    end if
    call commit_output(tmp, out, error)
    if (allocated(error)) call die(error%message)
    call MPI_Reduce(nfail, total, 1, MPI_INTEGER, MPI_SUM, 0, MPI_COMM_WORLD)
    if (rank == 0) write (stdout, '(a,i0,a,a,a)') "veslide-batch: ", nranks, " rank files ", base, &
        ".rank*.h5 written; join them with postproc/merge_ranks.py"
    if (rank == 0 .and. total > 0) write (stderr, '(a,i0,a)') "veslide-batch: NOT CONVERGED in ", total, " case(s)"
    call MPI_Finalize()
    if (total > 0 .and. rank == 0) stop 2, quiet=.true.   ! a controlled exit: the message is printed above

contains

    subroutine die(message)
        character(len=*), intent(in) :: message
        write (stderr, '(a)') message
        call MPI_Abort(MPI_COMM_WORLD, 1)
        stop 1, quiet=.true.
    end subroutine die

end program veslide_batch
