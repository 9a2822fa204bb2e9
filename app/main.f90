!> veslide FILE.nml [--output PATH] [--overwrite] [--quiet]
!> Runs the case a namelist describes and writes its HDF5 result; see README.md.
program veslide_main
    use, intrinsic :: iso_fortran_env, only: stderr => error_unit, stdout => output_unit
    use veslide_kinds, only: dp
    use veslide_error, only: error_t
    use veslide_config, only: config_t, read_config
    use veslide_run, only: case_t, run_case, write_case, prepare_output, commit_output, discard_output
    use veslide_analysis, only: contact_area_fraction, mean_separation
    use veslide_surface, only: rms_height
    use veslide_version, only: version_string
    use veslide_sweep, only: run_sweep
    implicit none
    type(config_t) :: cfg
    type(case_t) :: c
    type(error_t), allocatable :: error
    character(len=:), allocatable :: input, output, tmp, arg
    logical :: overwrite, quiet
    integer :: i, n

    overwrite = .false.; quiet = .false.
    allocate (character(len=0) :: input, output)
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
            output = argument(i)
        case ('--overwrite')
            overwrite = .true.
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

    call read_config(input, cfg, error)
    if (allocated(error)) call die(error%message)
    if (len(output) > 0) cfg%output_file = output
    if (overwrite) cfg%overwrite = .true.
    call prepare_output(cfg%output_file, cfg%overwrite, tmp, error)
    if (allocated(error)) call die(error%message)

    if (cfg%is_sweep) then
        block
            integer :: nfail
            call run_sweep(cfg, tmp, nfail, error, quiet=quiet)
            if (allocated(error)) then
                call discard_output(tmp); call die(error%message)
            end if
            call commit_output(tmp, cfg%output_file, error)
            if (allocated(error)) call die(error%message)
            if (.not. quiet) write (stdout, '(a)') "veslide: study written to "//cfg%output_file
            if (nfail > 0) then
                write (stderr, '(a,i0,a)') "veslide: NOT CONVERGED in ", nfail, &
                    " case(s) (see /summary converged)"
                stop 2, quiet=.true.   ! a controlled exit: the message is printed above
            end if
            stop
        end block
    end if
    call run_case(cfg, c, error)
    if (allocated(error)) call die(error%message)
    call write_case(tmp, cfg, c, error)
    if (allocated(error)) then
        call discard_output(tmp); call die(error%message)
    end if
    call commit_output(tmp, cfg%output_file, error)
    if (allocated(error)) then
        call discard_output(tmp); call die(error%message)
    end if

    if (.not. quiet) call summary()
    if (.not. c%state%converged) then
        write (stderr, '(a,es9.2,a,es9.2,a,i0,a)') "veslide: NOT CONVERGED: residual ", c%state%residual, &
            " > tolerance ", cfg%tolerance, " after ", c%state%iterations, &
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

    subroutine die(message)
        character(len=*), intent(in) :: message
        write (stderr, '(a)') message
        stop 1, quiet=.true.
    end subroutine die

    subroutine usage()
        write (stdout, '(a)') "usage: veslide FILE.nml [--output PATH] [--overwrite] [--quiet]", &
            "  Solves the steady sliding contact the namelist describes and writes an HDF5 file", &
            "  (default &output file). Exit status: 0 converged, 1 bad input or I/O error,", &
            "  2 solved but not converged (the file is written, /scalars/converged = 0)."
    end subroutine usage

    subroutine summary()
        write (stdout, '(a)') "veslide "//version_string()//": "//cfg%path//" -> "//cfg%output_file
        write (stdout, '(a,i0,a,i0,a,a,a,a,a,a)') "  grid ", size(c%h, 1), " x ", size(c%h, 2), &
            ", surface ", trim(cfg%surface_kind), ", material ", trim(cfg%model), ", kernel ", trim(cfg%kernel)
        write (stdout, '(a,es12.5,a)') "  rms height            ", rms_height(c%h), " m"
        write (stdout, '(a,es12.5,a)') "  nominal pressure      ", cfg%mean_pressure_pa, " Pa"
        write (stdout, '(a,f12.8)') "  contact area fraction ", contact_area_fraction(c%state%p)
        write (stdout, '(a,es12.5,a,f9.5,a)') "  mean separation       ", mean_separation(c%state%g), " m (", &
            mean_separation(c%state%g)/max(rms_height(c%h), tiny(1.0_dp)), " h_rms)"
        write (stdout, '(a,es12.5,a)') "  max pressure          ", maxval(c%state%p), " Pa"
        if (norm2(c%velocity_m_s) > 0.0_dp .and. .not. c%kernel%symmetric) then
            write (stdout, '(a,es12.5)') "  friction coefficient  ", &
                -dot_product(c%force_pa, c%velocity_m_s)/norm2(c%velocity_m_s)/cfg%mean_pressure_pa
        end if
        write (stdout, '(a,a,a,i0,a,i0,a,es9.2,a,l1)') "  solver ", c%state%method, ": ", c%state%iterations, &
            " iterations, ", c%state%operator_applications, " FFT pairs, residual ", c%state%residual, &
            ", converged ", c%state%converged
        write (stdout, '(a,f8.3,a,f8.3,a,f8.3,a)') "  time: surface ", c%surface_seconds, " s, kernel ", &
            c%kernel_seconds, " s, solve ", c%solve_seconds, " s"
    end subroutine summary

end program veslide_main
