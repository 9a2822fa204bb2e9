!> Namelist input, error paths, measured topographies and the HDF5 output contract
module test_veslide_config
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use veslide_kinds, only: dp
    use veslide_error, only: fatal_error
    use veslide_config, only: config_t, read_config
    use veslide_fftw, only: fft2d_t
    use veslide_hdf5, only: h5file_t
    use veslide_run, only: case_t, build_surface, run_case, write_case, prepare_output, commit_output
    use veslide_version, only: veslide_version_number
    use veslide_sweep, only: run_sweep, seed_statistics
    use testsuite, only: error_t, unittest_t, new_unittest, check, report
    use test_support, only: unique_name, write_text
    implicit none
    private
    public :: collect_config

contains

    subroutine collect_config(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("defaults-and-values", test_values), &
            new_unittest("out-of-range-names-group-variable-range", test_out_of_range), &
            new_unittest("unknown-variable", test_unknown_variable), &
            new_unittest("misspelt-group", test_misspelt_group), &
            new_unittest("missing-input-file", test_missing_file), &
            new_unittest("bad-enumeration", test_bad_enum), &
            new_unittest("non-periodic-wave", test_nonperiodic_wave), &
            new_unittest("height-file-read", test_height_file), &
            new_unittest("height-file-not-square", test_height_not_square), &
            new_unittest("height-file-nan", test_height_nan), &
            new_unittest("height-file-missing-dataset", test_height_missing), &
            new_unittest("output-exists-not-overwritten", test_output_exists), &
            new_unittest("output-unwritable", test_output_unwritable), &
            new_unittest("hdf5-contract", test_hdf5_contract), &
            new_unittest("version-matches-fpm-toml", test_version), &
            new_unittest("sweep-cases-equal-single-runs", test_sweep), &
            new_unittest("sweep-over-height-file", test_sweep_file), &
            new_unittest("seed-statistics-axial", test_seed_statistics) &
            ]
    end subroutine collect_config

    !> Read `text` as a namelist file; return the error (if any) in `error`
    subroutine read_text(tag, text, cfg, error)
        character(len=*), intent(in) :: tag, text
        type(config_t), intent(out) :: cfg
        type(error_t), allocatable, intent(out) :: error
        character(len=:), allocatable :: path
        integer :: u
        path = unique_name(tag//'.nml')
        call write_text(path, text)
        call read_config(path, cfg, error)
        open (newunit=u, file=path); close (u, status='delete')
    end subroutine read_text

    !> Passes when reading `text` fails with a message containing every one of `words`
    subroutine expect_message(tag, text, words, error)
        character(len=*), intent(in) :: tag, text, words(:)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        type(error_t), allocatable :: e
        integer :: k
        call read_text(tag, text, cfg, e)
        call expect_words(e, words, error)
    end subroutine expect_message

    !> Passes when `e` is an error whose message contains every one of `words`
    subroutine expect_words(e, words, error)
        type(error_t), allocatable, intent(in) :: e
        character(len=*), intent(in) :: words(:)
        type(error_t), allocatable, intent(out) :: error
        integer :: k
        if (.not. allocated(e)) then
            call fatal_error(error, "no error raised"); return
        end if
        do k = 1, size(words)
            if (index(e%message, trim(words(k))) == 0) then
                call fatal_error(error, "message lacks '"//trim(words(k))//"': "//e%message); return
            end if
        end do
    end subroutine expect_words

    subroutine test_values(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        call read_text('values', "&grid nx = 32, ny = 16 / &surface k_cut = 6 /"//new_line('a')// &
                       "&material model='creep', e0_pa=1e6, creep_c_per_pa=1e-7,2e-7, creep_tau_s=1e-3,1e-2 /", &
                       cfg, error)
        if (allocated(error)) return
        call check(error, cfg%nx == 32 .and. cfg%ny == 16, "grid"); if (allocated(error)) return
        call check(error, cfg%ly_m, 0.005_dp, "ly_m defaults to lx_m*ny/nx", rel=1.0e-15_dp); if (allocated(error)) return
        call check(error, size(cfg%prony_coef) == 2 .and. cfg%prony_time_s(2) == 1.0e-2_dp, "Prony terms")
        if (allocated(error)) return
        call check(error, index(cfg%text, "creep_tau_s") > 0, "input text kept verbatim"); if (allocated(error)) return
        call read_text('values2', "&solver kernel = 'collocation-alias' /", cfg, error); if (allocated(error)) return
        call check(error, cfg%kernel == 'collocation-alias', "the longest kernel name survives")
    end subroutine test_values

    subroutine test_out_of_range(error)
        type(error_t), allocatable, intent(out) :: error
        character(len=32) :: w(4)
        w = [character(len=32) :: "&grid nx", "= 0", "allowed", "1 to 65536"]
        call expect_message('range1', "&grid nx = 0 /", w, error); if (allocated(error)) return
        w = [character(len=32) :: "&material poisson", "0.7", "allowed", "0 to 0.5"]
        call expect_message('range2', "&material poisson = 0.7 /", w, error); if (allocated(error)) return
        w = [character(len=32) :: "&load mean_pressure_pa", "allowed", "> 0", ""]
        call expect_message('range3', "&load mean_pressure_pa = -1 /", w(1:3), error); if (allocated(error)) return
        w = [character(len=32) :: "&surface k_cut", "Nyquist", "", ""]
        call expect_message('range4', "&grid nx = 64, ny = 64 / &surface k_cut = 40 /", w(1:2), error)
        if (allocated(error)) return
        w = [character(len=32) :: "&material", "one_term", "", ""]
        w = [character(len=32) :: "&material ratio", "> 1", "", ""]
        call expect_message('range5', "&material model='one_term', ratio = 0.5 /", w(1:2), error)
    end subroutine test_out_of_range

    subroutine test_unknown_variable(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('unknown', "&grid nx = 32, nz = 4 /", [character(len=16) :: "&grid", "nz"], error)
    end subroutine test_unknown_variable

    subroutine test_misspelt_group(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        call expect_message('group', "&grid nx = 32 / &surfce kind = 'flat' /", &
                            [character(len=24) :: "unknown namelist group", "&surfce"], error)
        if (allocated(error)) return
        ! an ampersand inside a comment or a string is not a group
        call read_text('group2', "&grid nx = 32, ny = 32 / &surface k_cut = 8 / ! see &notes"//new_line('a')// &
                       "&output file = 'a&b.h5' /", cfg, error)
    end subroutine test_misspelt_group

    subroutine test_missing_file(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        type(error_t), allocatable :: e
        call read_config('/nonexistent/veslide.nml', cfg, e)
        call check(error, allocated(e), "no error for a missing file"); if (allocated(error)) return
        call check(error, index(e%message, '/nonexistent/veslide.nml') > 0, "message lacks the file name: "//e%message)
    end subroutine test_missing_file

    subroutine test_bad_enum(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('enum', "&solver kernel = 'fancy' /", &
                            [character(len=16) :: "&solver kernel", "'fancy'", "galerkin"], error)
    end subroutine test_bad_enum

    subroutine test_nonperiodic_wave(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('wave', "&grid nx=64, ny=64, lx_m=1 / &surface kind='cosine', amplitude_m=1e-6, "// &
                            "wavelength_m=0.3 /", [character(len=24) :: "&surface wavelength_m", "periodic"], error)
    end subroutine test_nonperiodic_wave

    !> Write a height dataset; `lx` > 0 adds the length_m attribute
    subroutine write_heights(path, h, lx, error)
        character(len=*), intent(in) :: path
        real(dp), intent(in) :: h(:, :), lx
        type(error_t), allocatable, intent(out) :: error
        type(h5file_t) :: f
        call f%open(path, 'w', error); if (allocated(error)) return
        call f%write('/height_m', h, error); if (allocated(error)) return
        if (lx > 0.0_dp) call f%writeattr('/height_m', 'length_m', lx, error)
        call f%close()
    end subroutine write_heights

    !> Build the surface of a config naming a height file; returns the error of build_surface
    subroutine surface_from(tag, h, lx, cfg, hout, error, extra)
        character(len=*), intent(in) :: tag
        real(dp), intent(in) :: h(:, :), lx
        type(config_t), intent(out) :: cfg
        real(dp), allocatable, intent(out) :: hout(:, :)
        type(error_t), allocatable, intent(out) :: error
        character(len=*), intent(in), optional :: extra
        character(len=:), allocatable :: h5, more
        type(fft2d_t) :: fft
        integer :: u
        h5 = unique_name(tag//'.h5')
        more = ''
        if (present(extra)) more = extra
        call write_heights(h5, h, lx, error); if (allocated(error)) return
        call read_text(tag, "&surface kind='file', file='"//h5//"' "//more//" /", cfg, error)
        if (allocated(error)) return
        call build_surface(cfg, fft, hout, error)
        open (newunit=u, file=h5); close (u, status='delete')
    end subroutine surface_from

    subroutine test_height_file(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        real(dp) :: h(8, 8)
        real(dp), allocatable :: hout(:, :)
        call random_number(h)
        call surface_from('hread', h, 2.0e-3_dp, cfg, hout, error); if (allocated(error)) return
        call check(error, all(hout == h), "heights changed on the way"); if (allocated(error)) return
        call check(error, cfg%nx == 8 .and. cfg%ny == 8 .and. cfg%lx_m == 2.0e-3_dp, "grid from the file")
    end subroutine test_height_file

    subroutine expect_surface_error(tag, h, lx, words, error)
        character(len=*), intent(in) :: tag, words(:)
        real(dp), intent(in) :: h(:, :), lx
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        real(dp), allocatable :: hout(:, :)
        type(error_t), allocatable :: e
        integer :: k
        call surface_from(tag, h, lx, cfg, hout, e)
        call expect_words(e, words, error)
    end subroutine expect_surface_error

    subroutine test_height_not_square(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp) :: h(8, 6)
        h = 0
        call expect_surface_error('hsq', h, 1.0_dp, [character(len=16) :: "&surface file", "square"], error)
    end subroutine test_height_not_square

    subroutine test_height_nan(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp) :: h(8, 8)
        h = 0; h(3, 4) = ieee_value(1.0_dp, ieee_quiet_nan)
        call expect_surface_error('hnan', h, 1.0_dp, [character(len=16) :: "&surface file", "NaN"], error)
        if (allocated(error)) return
        h(3, 4) = 0
        call expect_surface_error('hlen', h, 0.0_dp, [character(len=16) :: "length_m", "lx_m"], error)
    end subroutine test_height_nan

    subroutine test_height_missing(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        real(dp), allocatable :: hout(:, :)
        type(error_t), allocatable :: e
        real(dp) :: h(4, 4)
        h = 0
        call surface_from('hmiss', h, 1.0_dp, cfg, hout, e, extra="dataset='/topo'")
        call check(error, allocated(e), "no error"); if (allocated(error)) return
        call check(error, index(e%message, "/topo") > 0, "message lacks the dataset: "//e%message)
    end subroutine test_height_missing

    !> An existing result is never replaced unless asked, and is left untouched
    subroutine test_output_exists(error)
        type(error_t), allocatable, intent(out) :: error
        character(len=:), allocatable :: path, tmp
        type(error_t), allocatable :: e
        character(len=16) :: line
        integer :: u
        path = unique_name('exists.h5')
        call write_text(path, 'earlier result')
        call prepare_output(path, .false., tmp, e)
        call check(error, allocated(e), "existing output accepted"); if (allocated(error)) return
        call check(error, index(e%message, "overwrite") > 0, "message does not say how: "//e%message)
        if (allocated(error)) return
        open (newunit=u, file=path, status='old'); read (u, '(a)') line; close (u, status='delete')
        call check(error, line == 'earlier result', "earlier result changed")
    end subroutine test_output_exists

    subroutine test_output_unwritable(error)
        type(error_t), allocatable, intent(out) :: error
        character(len=:), allocatable :: tmp
        type(error_t), allocatable :: e
        call prepare_output('/nonexistent-dir/out.h5', .true., tmp, e)
        call check(error, allocated(e), "unwritable path accepted"); if (allocated(error)) return
        call check(error, index(e%message, "/nonexistent-dir/out.h5") > 0, "message lacks the path: "//e%message)
    end subroutine test_output_unwritable

    !> A small case end to end: the paths and units of the output contract
    subroutine test_hdf5_contract(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        type(case_t) :: c
        type(h5file_t) :: f
        character(len=:), allocatable :: out, tmp
        character(len=40) :: paths(12)
        real(dp) :: a
        integer :: k, u
        out = unique_name('contract.h5')
        call read_text('contract', "&grid nx = 32, ny = 32 / &surface k_cut = 8 / &solver fft_planner='estimate' /"// &
                       " &output file = '"//out//"' /", cfg, error)
        if (allocated(error)) return
        call prepare_output(cfg%output_file, .false., tmp, error); if (allocated(error)) return
        call run_case(cfg, c, error); if (allocated(error)) return
        call write_case(tmp, cfg, c, error); if (allocated(error)) return
        call commit_output(tmp, out, error); if (allocated(error)) return
        paths = [character(len=40) :: '/scalars/contact_area_fraction', '/scalars/mean_separation_m', &
                 '/scalars/rms_height_m', '/scalars/max_pressure_pa', '/scalars/iterations', '/scalars/converged', &
                 '/scalars/residual', '/fields/height_m', '/fields/pressure_pa', '/fields/displacement_m', &
                 '/fields/gap_m', '/input/namelist']
        call f%open(out, 'r', error); if (allocated(error)) return
        do k = 1, size(paths)
            if (.not. f%exists(trim(paths(k)))) then
                call fatal_error(error, "missing "//trim(paths(k))); return
            end if
            if (.not. f%attr_exists(trim(paths(k)), 'units')) then
                call fatal_error(error, "no units on "//trim(paths(k))); return
            end if
        end do
        call check(error, f%attr_exists('/', 'git_revision') .and. f%attr_exists('/', 'compiler') .and. &
                   f%attr_exists('/', 'seed') .and. f%attr_exists('/', 'hdf5_version') .and. &
                   f%attr_exists('/', 'veslide_version') .and. f%attr_exists('/', 'created'), "provenance attributes")
        if (allocated(error)) return
        call f%read_r0('/scalars/contact_area_fraction', a, error); if (allocated(error)) return
        call f%close()
        open (newunit=u, file=out); close (u, status='delete')
        call check(error, a, real(count(c%state%p > 0), dp)/1024.0_dp, "area read back", rel=0.0_dp)
    end subroutine test_hdf5_contract

    subroutine test_version(error)
        type(error_t), allocatable, intent(out) :: error
        character(len=256) :: line
        integer :: u, stat
        open (newunit=u, file='fpm.toml', status='old', action='read', iostat=stat)
        if (stat /= 0) then
            call fatal_error(error, "fpm.toml not found (tests run from the project root)"); return
        end if
        do
            read (u, '(a)', iostat=stat) line
            if (stat /= 0) exit
            if (index(line, 'version') == 1) exit
        end do
        close (u)
        call check(error, index(line, '"'//veslide_version_number//'"') > 0, &
                   "fpm.toml says "//trim(line)//", the code says "//veslide_version_number)
    end subroutine test_version

    !> A study of 2 seeds x 2 angles x 3 speeds: every case (kernel reused, warm-started along
    !> speed) equals the single run of its parameters to the solver tolerance
    subroutine test_sweep(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg, one
        type(case_t) :: c
        type(h5file_t) :: f
        character(len=:), allocatable :: out, base
        real(dp) :: fric, area, par(6), worst
        integer :: nfail, k, u
        integer(8) :: dims(7)
        integer :: rank
        logical :: is_double
        character(len=16) :: tag
        out = unique_name('sweep.h5')
        base = "&grid nx = 32, ny = 32 / &surface k_cut = 8, eccentricity = 0.5 / &solver fft_planner='estimate'"// &
               ", tolerance = 1e-12 / &material model='one_term' / &motion speed_m_s = 0.1 /"
        call read_text('sweep', base//" &sweep speeds_m_s = 0.01, 0.1, 1.0, alphas_deg = 0, 30, n_seeds = 2 /"// &
                       " &output fields = .false. /", cfg, error)
        if (allocated(error)) return
        call run_sweep(cfg, out, nfail, error, quiet=.true.); if (allocated(error)) return
        call check(error, nfail, 0, "cases not converged"); if (allocated(error)) return
        call f%open(out, 'r', error); if (allocated(error)) return
        call f%shape_of('/summary', dims, rank, is_double)
        call check(error, rank == 1 .and. dims(1) == 12, "summary rows"); if (allocated(error)) return
        call check(error, f%exists('/ensemble'), "ensemble table"); if (allocated(error)) return
        worst = 0
        do k = 1, 12, 5
            write (tag, '("/cases/",i6.6)') k
            call f%read_r0(trim(tag)//'/scalars/friction_coefficient', fric, error); if (allocated(error)) return
            call f%read_r0(trim(tag)//'/scalars/contact_area_fraction', area, error); if (allocated(error)) return
            call read_params(f, trim(tag)//'/parameters', par, error); if (allocated(error)) return
            call read_text('sweep-one', base, one, error); if (allocated(error)) return
            one%seed = nint(par(2), 8); one%alpha_deg = par(4); one%speed_m_s = par(6)
            call run_case(one, c, error); if (allocated(error)) return
            worst = max(worst, abs(fric + c%force_pa(1)/one%mean_pressure_pa)/abs(fric))
            call check(error, area, real(count(c%state%p > 0), dp)/1024, "area of case "//tag, rel=0.0_dp)
            if (allocated(error)) return
        end do
        call report("max rel. friction difference", worst)
        call check(error, worst <= 1.0e-8_dp, "sweep case differs from its single run")
        call f%close()
        open (newunit=u, file=out); close (u, status='delete')
    end subroutine test_sweep

    !> A speed sweep over a measured topography takes its grid and cell size from the file
    !> (&grid left unset), and its cases equal the single run of the same file
    subroutine test_sweep_file(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg, one
        type(case_t) :: c
        type(h5file_t) :: f
        character(len=:), allocatable :: out, h5, base
        real(dp) :: h(16, 16), fric
        integer :: nfail, u, i, j, rank
        integer(8) :: dims(7)
        logical :: is_double
        out = unique_name('sweepfile.h5'); h5 = unique_name('sweepfile-heights.h5')
        do j = 1, 16
            do i = 1, 16
                h(i, j) = 1.0e-6_dp*(cos(6.283185307179586_dp*i/16)*sin(6.283185307179586_dp*2*j/16) + &
                                     0.5_dp*cos(6.283185307179586_dp*(3*i + j)/16))
            end do
        end do
        call write_heights(h5, h, 4.0e-3_dp, error); if (allocated(error)) return
        base = "&surface kind='file', file='"//h5//"' / &material model='one_term' / &solver fft_planner='estimate'"// &
               ", tolerance = 1e-12 / &load mean_pressure_pa = 1e5 / &output fields = .false. /"
        call read_text('sweepfile', base//" &sweep speeds_m_s = 0.001, 0.01 /", cfg, error); if (allocated(error)) return
        call run_sweep(cfg, out, nfail, error, quiet=.true.); if (allocated(error)) return
        call check(error, nfail, 0, "cases not converged"); if (allocated(error)) return
        call f%open(out, 'r', error); if (allocated(error)) return
        call f%shape_of('/summary', dims, rank, is_double)
        call check(error, rank == 1 .and. dims(1) == 2, "summary rows"); if (allocated(error)) return
        call f%read_r0('/cases/000002/scalars/friction_coefficient', fric, error); if (allocated(error)) return
        call f%close()
        call read_text('sweepfile-one', base//" &motion speed_m_s = 0.01 /", one, error); if (allocated(error)) return
        call run_case(one, c, error); if (allocated(error)) return
        call report("friction", fric)
        call check(error, fric, -c%force_pa(1)/one%mean_pressure_pa, "sweep case vs single run", rel=1.0e-8_dp)
        open (newunit=u, file=out); close (u, status='delete')
        open (newunit=u, file=h5); close (u, status='delete')
    end subroutine test_sweep_file

    !> Ensemble statistics: arithmetic for ordinary quantities, circular (modulo pi) for axes
    subroutine test_seed_statistics(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp), parameter :: pi = acos(-1.0_dp)
        real(dp) :: m, s
        call seed_statistics([1.0_dp, 2.0_dp, 3.0_dp, 6.0_dp], 0, m, s)
        call check(error, m, 3.0_dp, "mean", rel=1.0e-15_dp); if (allocated(error)) return
        call check(error, s, sqrt(14.0_dp/3.0_dp)/2.0_dp, "standard error", rel=1.0e-15_dp); if (allocated(error)) return
        ! theta in [0, pi): samples at 0.02, pi - 0.04, 0.05 average to an axis near 0.01, not pi/2
        call seed_statistics([0.02_dp, pi - 0.04_dp, 0.05_dp], 1, m, s)
        call check(error, m, 0.01_dp, "axial mean across 0 = pi", abs=1.0e-4_dp); if (allocated(error)) return
        call check(error, s, sqrt((0.01_dp**2 + 0.05_dp**2 + 0.04_dp**2)/2)/sqrt(3.0_dp), "axial standard error", &
                   rel=1.0e-3_dp)
        if (allocated(error)) return
        ! an axis across 0 from below: the mean stays in [0, pi)
        call seed_statistics([pi - 0.02_dp, pi - 0.04_dp, 0.0_dp], 1, m, s)
        call check(error, m, pi - 0.02_dp, "axial mean in [0, pi)", abs=1.0e-4_dp); if (allocated(error)) return
        ! phi in (-pi/2, pi/2]: samples about pi/2 = -pi/2
        call seed_statistics([pi/2 - 0.01_dp, -pi/2 + 0.03_dp], 2, m, s)
        call check(error, abs(abs(m) - (pi/2 - 0.01_dp)) < 1.0e-4_dp .and. s < 0.03_dp, "phi across +-pi/2")
    end subroutine test_seed_statistics

    subroutine read_params(f, name, par, error)
        type(h5file_t), intent(inout) :: f
        character(len=*), intent(in) :: name
        real(dp), intent(out) :: par(6)
        type(error_t), allocatable, intent(out) :: error
        real(dp) :: buf(6, 1)
        call f%read_r2(name, buf, error)
        par = buf(:, 1)
    end subroutine read_params

end module test_veslide_config
