!> The namelist input: one suite per group module (its defaults, reads and refusals, each refusal
!> checked for the group, the variable and the allowed range it names) and one for the composed
!> configuration (group names, the file, the checks across groups)
module test_veslide_config
    use veslide_kinds, only: dp
    use veslide_error, only: fatal_error
    use veslide_config, only: config_t, read_config, case_law
    use veslide_contact_law, only: contact_law_t, LAW_DUGDALE, ADH_RANGE
    use veslide_output, only: prepare_output
    use testsuite, only: error_t, unittest_t, new_unittest, check
    use test_support, only: unique_name, write_text
    implicit none
    private
    public :: collect_config, collect_config_grid, collect_config_surface, collect_config_material, &
              collect_config_load, collect_config_motion, collect_config_solver, collect_config_analysis, &
              collect_config_sweep, collect_config_output, collect_config_interface, read_text, expect_words

contains

    subroutine collect_config(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("defaults-and-values", test_values), &
            new_unittest("misspelt-group", test_misspelt_group), &
            new_unittest("missing-input-file", test_missing_file), &
            new_unittest("k-cut-below-the-grid-nyquist", test_kcut_nyquist), &
            new_unittest("non-periodic-wave", test_nonperiodic_wave), &
            new_unittest("pk-refused-for-sliding-viscoelastic", test_pk_visco), &
            new_unittest("sweep-angles-need-a-random-surface", test_sweep_kind), &
            new_unittest("group-given-twice", test_duplicate_group), &
            new_unittest("text-outside-groups", test_text_outside), &
            new_unittest("binary-file", test_binary), &
            new_unittest("no-group-at-all", test_no_group), &
            new_unittest("default-k-cut-follows-a-small-grid", test_default_kcut), &
            new_unittest("default-output-is-the-namelist-name", test_default_output), &
            new_unittest("sweep-of-temperatures-without-a-shift-names-them", test_temperatures_without_shift), &
            new_unittest("no-op-inputs-warn", test_warnings) &
            ]
    end subroutine collect_config

    subroutine collect_config_grid(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("nx-out-of-range", test_grid_nx), &
            new_unittest("ly-default-keeps-cells-square", test_grid_ly), &
            new_unittest("unknown-variable", test_unknown_variable), &
            new_unittest("type-error-names-the-variable", test_type_error), &
            new_unittest("type-error-in-a-multi-line-group-on-one-line", test_type_error_lines), &
            new_unittest("cell-size-absurd", test_grid_absurd) &
            ]
    end subroutine collect_config_grid

    subroutine collect_config_surface(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("hurst-out-of-range", test_surface_hurst), &
            new_unittest("kind-unknown", test_surface_kind), &
            new_unittest("exactly-one-roughness-target", test_surface_target) &
            ]
    end subroutine collect_config_surface

    subroutine collect_config_material(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("poisson-out-of-range", test_material_poisson), &
            new_unittest("ratio-must-exceed-one", test_material_ratio), &
            new_unittest("prony-lists-without-gaps", test_material_prony), &
            new_unittest("infinite-prony-time", test_material_infinite), &
            new_unittest("temperature-shift-needs-its-constants", test_material_shift), &
            new_unittest("shift-table-read-and-checked", test_material_shift_table), &
            new_unittest("prony-series-of-256-terms", test_material_long_series) &
            ]
    end subroutine collect_config_material

    subroutine collect_config_load(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [new_unittest("pressure-positive", test_load), &
                 new_unittest("adhesion-law-and-parameters", test_adhesion), &
                 new_unittest("tensile-load-with-adhesion", test_adhesion_load), &
                 new_unittest("adhesion-in-motion-takes-gcg", test_adhesion_motion), &
                 new_unittest("load-path-of-approaches", test_sweep_approaches)]
    end subroutine collect_config_load

    subroutine collect_config_motion(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [new_unittest("direction-in-range", test_motion)]
    end subroutine collect_config_motion

    subroutine collect_config_interface(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("shear-coefficient-default-and-value", test_interface_values), &
            new_unittest("shear-coefficient-in-range", test_interface_range), &
            new_unittest("symmetric-solvers-refused-with-shear", test_interface_solvers), &
            new_unittest("shear-on-a-layer-refused", test_interface_layer), &
            new_unittest("elastic-speed-warning-names-the-shear", test_interface_warning) &
            ]
    end subroutine collect_config_interface

    subroutine collect_config_solver(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("bad-enumeration", test_bad_enum), &
            new_unittest("tolerance-in-range", test_solver_tolerance), &
            new_unittest("anderson-memory-in-range", test_anderson_memory), &
            new_unittest("longest-kernel-name-survives", test_kernel_name), &
            new_unittest("overlong-choice-texts-refused", test_overlong_choices) &
            ]
    end subroutine collect_config_solver

    subroutine collect_config_analysis(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("band-defaults-to-k-cut", test_analysis_band), &
            new_unittest("n-theta-in-range", test_analysis_ntheta) &
            ]
    end subroutine collect_config_analysis

    subroutine collect_config_sweep(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("log-range-expanded", test_sweep_range), &
            new_unittest("range-needs-two-speeds", test_sweep_bad_range), &
            new_unittest("n-seeds-from-the-surface-seed", test_sweep_seeds), &
            new_unittest("range-without-n-speeds", test_sweep_range_no_n), &
            new_unittest("list-with-a-gap", test_sweep_gap), &
            new_unittest("most-negative-double-is-a-value", test_sweep_sentinel) &
            ]
    end subroutine collect_config_sweep

    subroutine collect_config_output(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [new_unittest("file-not-empty", test_output_file), &
                 new_unittest("file-name-too-long", test_output_long), &
                 new_unittest("fields-by-default-for-a-case-not-a-study", test_output_fields)]
    end subroutine collect_config_output

    !> Fields are written for a single case unless refused, and for a study only when asked
    subroutine test_output_fields(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        character(len=*), parameter :: study = " &material model = 'one_term' / &sweep speeds_m_s = 0.1, 1 /"
        call read_text('f1', "&grid nx = 32 / &surface k_cut = 8 /", cfg, error); if (allocated(error)) return
        call check(error, cfg%output%fields, "a case writes its fields"); if (allocated(error)) return
        call read_text('f2', "&grid nx = 32 / &surface k_cut = 8 / &output fields = .false. /", cfg, error)
        if (allocated(error)) return
        call check(error, .not. cfg%output%fields, "a case told not to"); if (allocated(error)) return
        call read_text('f3', "&grid nx = 32 / &surface k_cut = 8 /"//study, cfg, error); if (allocated(error)) return
        call check(error, .not. cfg%output%fields, "a study writes no fields by default"); if (allocated(error)) return
        call read_text('f4', "&grid nx = 32 / &surface k_cut = 8 / &output fields = .true. /"//study, cfg, error)
        if (allocated(error)) return
        call check(error, cfg%output%fields, "a study asked for its fields"); if (allocated(error)) return
        call read_text('f5', "&grid nx = 32 / &surface k_cut = 8 / &output file = 'x.h5' /"//study, cfg, error)
        if (allocated(error)) return
        call check(error, .not. cfg%output%fields, "&output without fields in a study")
    end subroutine test_output_fields

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

    ! ------------------------------------------------------------------ the composed configuration

    subroutine test_values(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        call read_text('values', "&grid nx = 32, ny = 16 / &surface k_cut = 6 /"//new_line('a')// &
                       "&material model='creep', e0_pa=1e6, creep_c_per_pa=1e-7,2e-7, creep_tau_s=1e-3,1e-2 /", &
                       cfg, error)
        if (allocated(error)) return
        call check(error, cfg%grid%nx == 32 .and. cfg%grid%ny == 16, "grid"); if (allocated(error)) return
        call check(error, cfg%grid%ly_m, 0.005_dp, "ly_m defaults to lx_m*ny/nx", rel=1.0e-15_dp)
        if (allocated(error)) return
        call check(error, size(cfg%material%prony_coef) == 2 .and. cfg%material%prony_time_s(2) == 1.0e-2_dp, &
                   "Prony terms")
        if (allocated(error)) return
        call check(error, index(cfg%text, "creep_tau_s") > 0, "input text kept verbatim"); if (allocated(error)) return
        call check(error, cfg%surface%kind == 'self_affine' .and. cfg%solver%method == 'auto' .and. &
                   cfg%load%mean_pressure_pa == 32.0e3_dp .and. .not. cfg%sweep%is_study(), "defaults")
    end subroutine test_values

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

    !> A missing input and names the file system refuses (a component over 255 bytes) are
    !> refused with the reason in the system's own words
    subroutine test_missing_file(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        type(error_t), allocatable :: e
        character(len=:), allocatable :: tmp
        integer :: lock
        call read_config('/nonexistent/veslide.nml', cfg, e)
        call expect_words(e, [character(len=32) :: '/nonexistent/veslide.nml', 'No such file or directory'], error)
        if (allocated(error)) return
        ! a name the file system refuses: the reason in the system's words
        call read_config('/tmp/'//repeat('n', 300)//'.nml', cfg, e)
        call expect_words(e, [character(len=32) :: 'File name too long'], error)
        if (allocated(error)) return
        call prepare_output('/tmp/'//repeat('n', 300)//'.h5', .false., tmp, lock, e)
        call expect_words(e, [character(len=32) :: '.lock', 'in its directory: File name too long'], error)
    end subroutine test_missing_file

    subroutine test_kcut_nyquist(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('range4', "&grid nx = 64, ny = 64 / &surface k_cut = 40 /", &
                            [character(len=24) :: "&surface k_cut", "= 40", "Nyquist wavenumber 32"], error)
    end subroutine test_kcut_nyquist

    subroutine test_nonperiodic_wave(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('wave', "&grid nx=64, ny=64, lx_m=1 / &surface kind='cosine', amplitude_m=1e-6, "// &
                            "wavelength_m=0.3 /", [character(len=24) :: "&surface wavelength_m", "periodic"], error)
    end subroutine test_nonperiodic_wave

    subroutine test_pk_visco(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('pk', "&material model='one_term' / &motion speed_m_s = 0.1 / &solver method='pk' /", &
                            [character(len=24) :: "&solver method", "'pk'", "not symmetric"], error)
    end subroutine test_pk_visco

    subroutine test_sweep_kind(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('sweepkind', "&grid nx=64, ny=64, lx_m=1 / &surface kind='flat' / &sweep alphas_deg=0,45 /", &
                            [character(len=32) :: "&sweep alphas_deg/eccentricities", "self_affine"], error)
    end subroutine test_sweep_kind

    ! ------------------------------------------------------------------ the groups

    subroutine test_grid_nx(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('range1', "&grid nx = 0 /", [character(len=16) :: "&grid nx", "= 0", "allowed", &
                            "1 to 65536"], error)
    end subroutine test_grid_nx

    subroutine test_grid_ly(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        call read_text('ly', "&grid nx = 64, ny = 32, lx_m = 0.02 / &surface k_cut = 8 /", cfg, error)
        if (allocated(error)) return
        call check(error, cfg%grid%ly_m, 0.01_dp, "ly_m", rel=1.0e-15_dp)
    end subroutine test_grid_ly

    subroutine test_unknown_variable(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('unknown', "&grid nx = 32, nz = 4 /", [character(len=16) :: "&grid", "nz"], error)
    end subroutine test_unknown_variable

    subroutine test_surface_hurst(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('hurst', "&surface hurst = 1.2 /", [character(len=16) :: "&surface hurst", "1.2", &
                            "0 < hurst < 1"], error)
    end subroutine test_surface_hurst

    subroutine test_surface_kind(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('kind', "&surface kind = 'fractal' /", [character(len=16) :: "&surface kind", &
                            "'fractal'", "'file'"], error)
    end subroutine test_surface_kind

    subroutine test_surface_target(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('target', "&surface rms_height_m = 1e-6 /", [character(len=32) :: &
                            "&surface rms_slope/rms_height_m", "exactly one"], error)
    end subroutine test_surface_target

    subroutine test_material_poisson(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('range2', "&material poisson = 0.7 /", [character(len=24) :: "&material poisson", &
                            "0.7", "allowed", "0 to 0.5"], error)
    end subroutine test_material_poisson

    subroutine test_material_ratio(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('range5', "&material model='one_term', ratio = 0.5 /", &
                            [character(len=24) :: "&material ratio", "> 1"], error)
    end subroutine test_material_ratio

    subroutine test_material_prony(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('prony', "&material model='creep', e0_pa=1e6, creep_c_per_pa=1e-7,2e-7, "// &
                            "creep_tau_s=1e-3 /", [character(len=24) :: "&material", "creep_tau_s", &
                            "same number"], error)
    end subroutine test_material_prony

    subroutine test_load(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('range3', "&load mean_pressure_pa = -1 /", [character(len=24) :: &
                            "&load mean_pressure_pa", "allowed", "> 0"], error)
    end subroutine test_load

    !> &adhesion: a law by name, two of its three parameters (or three that agree), each in range
    subroutine test_adhesion(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('adh1', "&adhesion law = 'glue', energy_j_m2 = 0.05, range_m = 1e-9 /", &
                            [character(len=24) :: "&adhesion law = 'glue'", "'exponential'", "'dugdale'"], error)
        if (allocated(error)) return
        call expect_message('adh2', "&adhesion law = 'dugdale', energy_j_m2 = 0.05 /", &
                            [character(len=24) :: "needs two of", "stress_pa"], error)
        if (allocated(error)) return
        call expect_message('adh3', "&adhesion law = 'dugdale', energy_j_m2 = 0.05, range_m = 1e-9, stress_pa = 1e6 /", &
                            [character(len=24) :: "energy_j_m2", "differs"], error)
        if (allocated(error)) return
        call expect_message('adh4', "&adhesion law = 'exponential', energy_j_m2 = 0.05, range_m = -1e-9 /", &
                            [character(len=24) :: "&adhesion range_m", "allowed", "> 0"], error)
    end subroutine test_adhesion

    !> With a law the load may be tensile (and the law is the case's, its third parameter
    !> derived); without one a tensile load names &adhesion
    !> &sweep approaches_m: a path of approaches with an adhesive law, each in range, refused
    !> without a law, beside pressures_pa and beside &load approach_m
    subroutine test_sweep_approaches(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        type(error_t), allocatable :: e
        character(len=*), parameter :: law = "&adhesion law = 'dugdale', energy_j_m2 = 0.05, stress_pa = 5e7 /"
        call read_text('path1', law//new_line('a')//"&sweep approaches_m = 1e-7, -2e-7, 1e-7 /", cfg, e)
        call check(error, .not. allocated(e), "a path of approaches with &adhesion is read"); if (allocated(error)) return
        call check(error, size(cfg%sweep%approaches) == 3 .and. cfg%sweep%approaches(2) == -2.0e-7_dp .and. &
                   cfg%sweep%is_study(), "the approaches read, in order"); if (allocated(error)) return
        call expect_message('path2', "&sweep approaches_m = 1e-7, -2e-7 /", [character(len=24) :: &
                            "&sweep approaches_m", "adhesive law", "pressures_pa"], error)
        if (allocated(error)) return
        call expect_message('path3', law//new_line('a')//"&sweep approaches_m = 1e-7, 2, 0 /", &
                            [character(len=24) :: "&sweep approaches_m(2) =", "out of range", ">= -1 and <= 1 [m]"], error)
        if (allocated(error)) return
        call expect_message('path4', law//new_line('a')//"&sweep approaches_m = 1e-7, pressures_pa = 1e3 /", &
                            [character(len=24) :: "pressures_pa", "approaches_m", "give one"], error)
        if (allocated(error)) return
        call expect_message('path5', law//new_line('a')//"&load approach_m = 1e-7 /"//new_line('a')// &
                            "&sweep approaches_m = 1e-7, 0 /", [character(len=24) :: "&load approach_m", &
                            "&sweep approaches_m", "one place"], error)
    end subroutine test_sweep_approaches

    subroutine test_adhesion_load(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        type(error_t), allocatable :: e
        type(contact_law_t) :: law
        call read_text('adh5', "&adhesion law = 'dugdale', energy_j_m2 = 0.05, stress_pa = 5e7 /"// &
                       new_line('a')//"&load mean_pressure_pa = -100 /", cfg, e)
        call check(error, .not. allocated(e), "a tensile load with &adhesion is read"); if (allocated(error)) return
        law = case_law(cfg)
        call check(error, law%kind == LAW_DUGDALE .and. abs(law%param(ADH_RANGE) - 1.0e-9_dp) <= 1.0e-24_dp, &
                   "the case's law: Dugdale with range w/sigma0"); if (allocated(error)) return
        call expect_message('adh6', "&load mean_pressure_pa = -100 /", [character(len=24) :: &
                            "&load mean_pressure_pa", "&adhesion"], error)
        if (allocated(error)) return
        ! approach control: an adhesive law's, instead of the load, not beside a load sweep
        call read_text('adh8', "&adhesion law = 'dugdale', energy_j_m2 = 0.05, stress_pa = 5e7 /"// &
                       new_line('a')//"&load approach_m = 2e-7 /", cfg, e)
        call check(error, .not. allocated(e), "approach control with &adhesion is read"); if (allocated(error)) return
        call check(error, cfg%load%approach_m == 2.0e-7_dp, "the approach read"); if (allocated(error)) return
        call expect_message('adh9', "&load approach_m = 2e-7 /", [character(len=24) :: "&load approach_m", &
                            "adhesive law"], error)
        if (allocated(error)) return
        call expect_message('adh10', "&adhesion law = 'dugdale', energy_j_m2 = 0.05, stress_pa = 5e7 /"// &
                            new_line('a')//"&load approach_m = 2e-7, mean_pressure_pa = 10 /", &
                            [character(len=24) :: "both mean_pressure_pa", "approach_m"], error)
        if (allocated(error)) return
        call expect_message('adh11', "&adhesion law = 'dugdale', energy_j_m2 = 0.05, stress_pa = 5e7 /"// &
                            new_line('a')//"&load approach_m = 2e-7 /"//new_line('a')//"&sweep pressures_pa = 1, 2 /", &
                            [character(len=24) :: "&load approach_m", "&sweep pressures_pa"], error)
    end subroutine test_adhesion_load

    !> An adhesive law on a viscoelastic solid in motion: taken by gcg (its splitting); a hard-wall
    !> method asked for is refused at input, naming gcg
    subroutine test_adhesion_motion(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        character(len=*), parameter :: moving = "&grid nx = 32 / &surface k_cut = 8 / &material model = 'one_term' /"// &
                                        " &motion speed_m_s = 0.1 /"// &
                                        " &adhesion law = 'exponential', energy_j_m2 = 0.05, range_m = 1e-9 /"
        ! 'auto' (gcg's splitting) takes it; a hard-wall method is refused, naming gcg
        call read_text('adh7', moving, cfg, error); if (allocated(error)) return
        call expect_message('adh8', moving//" &solver method = 'pdr' /", &
                            [character(len=24) :: "&solver method = 'pdr'", "'exponential'", "'gcg'"], error)
    end subroutine test_adhesion_motion

    !> &interface is optional (mu_f = 0, no shear) and reads its one variable
    subroutine test_interface_values(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        call read_text('if0', "&grid nx = 32 / &surface k_cut = 8 /", cfg, error); if (allocated(error)) return
        call check(error, cfg%interface%shear_coefficient == 0.0_dp, "the default is no shear")
        if (allocated(error)) return
        call read_text('if1', "&grid nx = 32 / &surface k_cut = 8 / &interface shear_coefficient = 0.35 /", cfg, error)
        if (allocated(error)) return
        call check(error, cfg%interface%shear_coefficient == 0.35_dp, "the value read")
    end subroutine test_interface_values

    !> Negative, not finite, above 10, or not a number: refused naming the group, variable and range
    subroutine test_interface_range(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('if2', "&interface shear_coefficient = -0.1 /", [character(len=32) :: &
                            "&interface shear_coefficient", "-0.1", "allowed: 0 to 10"], error)
        if (allocated(error)) return
        call expect_message('if3', "&interface shear_coefficient = NaN /", [character(len=32) :: &
                            "&interface shear_coefficient", "NaN", "0 to 10"], error)
        if (allocated(error)) return
        call expect_message('if4', "&interface shear_coefficient = Inf /", [character(len=32) :: &
                            "&interface shear_coefficient", "0 to 10"], error)
        if (allocated(error)) return
        call expect_message('if5', "&interface shear_coefficient = 12 /", [character(len=32) :: &
                            "&interface shear_coefficient", "12", "0 to 10"], error)
        if (allocated(error)) return
        call expect_message('if6', "&interface shear_coefficient = 'high' /", [character(len=40) :: &
                            "&interface shear_coefficient = 'high'", "a real number"], error)
        if (allocated(error)) return
        call expect_message('if7', "&interface friction = 0.3 /", [character(len=32) :: &
                            "&interface friction", "no such variable", "shear_coefficient"], error)
    end subroutine test_interface_range

    !> With shear on a compressible solid the operator is not symmetric, elastic or not, at any
    !> speed: pk and bccg are refused by the input, naming the shear; at nu = 1/2 (beta = 0) and
    !> on a grid the shear's direction does not reach (2 cells along x, shear along x) they run
    subroutine test_interface_solvers(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        character(len=*), parameter :: base = "&grid nx = 32 / &surface k_cut = 8 / &interface shear_coefficient = 0.5 /"
        call expect_message('if8', base//" &material poisson = 0.3 / &solver method = 'pk' /", [character(len=40) :: &
                            "&solver method = 'pk'", "not symmetric", "&interface shear_coefficient", "'pdr'"], error)
        if (allocated(error)) return
        call expect_message('if9', base//" &material poisson = 0.3 / &motion direction_deg = 90 /"// &
                            " &solver method = 'bccg' /", [character(len=40) :: "&solver method = 'bccg'", &
                            "not symmetric"], error)
        if (allocated(error)) return
        call read_text('if10', base//" &material poisson = 0.5 / &solver method = 'pk' /", cfg, error)
        if (allocated(error)) return
        call read_text('if11', "&grid nx = 2, ny = 16, lx_m = 0.01 / &surface kind = 'flat' /"// &
                       " &interface shear_coefficient = 0.5 / &material poisson = 0.3 / &solver method = 'pk' /", &
                       cfg, error)
    end subroutine test_interface_solvers

    !> A layer's normal-tangential coupling is not the half-space's: refused with the reason
    subroutine test_interface_layer(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('if12', "&grid nx = 32 / &surface k_cut = 8 / &interface shear_coefficient = 0.2 /"// &
                            " &material thickness_m = 1e-3, poisson = 0.5 /", [character(len=48) :: &
                            "&interface shear_coefficient = 0.2", "&material thickness_m", &
                            "not available", "not zero even at poisson = 0.5"], error)
    end subroutine test_interface_layer

    !> On an elastic solid a speed changes nothing; with shear the warning does not say the
    !> friction is zero
    subroutine test_interface_warning(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        call read_text('if13', "&grid nx = 32 / &surface k_cut = 8 / &motion speed_m_s = 0.1 /"// &
                       " &interface shear_coefficient = 0.2 / &material poisson = 0.3 /", cfg, error)
        if (allocated(error)) return
        call check(error, size(cfg%warnings) == 1, "one warning"); if (allocated(error)) return
        call check(error, cfg%warnings(1)%code == 'elastic-speeds' .and. index(cfg%warnings(1)%text, "zero") == 0 &
                   .and. index(cfg%warnings(1)%text, "interfacial shear") > 0, "warning text: "//cfg%warnings(1)%text)
    end subroutine test_interface_warning

    subroutine test_motion(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('motion', "&motion direction_deg = 400 /", [character(len=24) :: &
                            "&motion direction_deg", "400", "-360 to 360"], error)
    end subroutine test_motion

    subroutine test_bad_enum(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('enum', "&solver kernel = 'fancy' /", &
                            [character(len=16) :: "&solver kernel", "'fancy'", "galerkin"], error)
    end subroutine test_bad_enum

    subroutine test_solver_tolerance(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('tol', "&solver tolerance = 1e-20 /", [character(len=24) :: "&solver tolerance", &
                            "1e-13 to 1e-2"], error)
    end subroutine test_solver_tolerance

    !> -1 (each method's own) by default; below -1 refused with the allowed range
    subroutine test_anderson_memory(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        call read_text('am', "&solver method = 'pdr' /", cfg, error); if (allocated(error)) return
        call check(error, cfg%solver%anderson_memory == -1, "the default is not -1"); if (allocated(error)) return
        call expect_message('am2', "&solver anderson_memory = -2 /", [character(len=28) :: &
                            "&solver anderson_memory", "-2", "-1 (the method's default)"], error)
    end subroutine test_anderson_memory

    subroutine test_kernel_name(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        call read_text('values2', "&solver kernel = 'collocation-alias' /", cfg, error); if (allocated(error)) return
        call check(error, cfg%solver%kernel == 'collocation-alias', "the longest kernel name survives")
    end subroutine test_kernel_name

    subroutine test_analysis_band(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        call read_text('band', "&grid nx = 64, ny = 64 / &surface k_cut = 12 / &analysis anisotropy = .true. /", &
                       cfg, error)
        if (allocated(error)) return
        call check(error, cfg%analysis%zeta2, 12.0_dp, "zeta2 = 0 means k_cut", rel=0.0_dp)
    end subroutine test_analysis_band

    subroutine test_analysis_ntheta(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('ntheta', "&analysis n_theta = 2 /", [character(len=24) :: "&analysis n_theta", &
                            "4 to 100000"], error)
    end subroutine test_analysis_ntheta

    subroutine test_sweep_range(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        call read_text('range', "&sweep speed_min_m_s = 1e-3, speed_max_m_s = 10, n_speeds = 5 /", cfg, error)
        if (allocated(error)) return
        call check(error, size(cfg%sweep%speeds) == 5 .and. cfg%sweep%is_study(), "five speeds")
        if (allocated(error)) return
        call check(error, cfg%sweep%speeds(3), 0.1_dp, "log spacing", rel=1.0e-14_dp)
    end subroutine test_sweep_range

    subroutine test_sweep_bad_range(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('badrange', "&sweep speed_min_m_s = 1e-3, speed_max_m_s = 10, n_speeds = 1 /", &
                            [character(len=24) :: "&sweep n_speeds", "2 <= n_speeds"], error)
    end subroutine test_sweep_bad_range

    subroutine test_sweep_seeds(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        call read_text('seeds', "&surface seed = 41 / &sweep n_seeds = 3 /", cfg, error)
        if (allocated(error)) return
        call check(error, all(cfg%sweep%seeds == [41_8, 42_8, 43_8]), "seeds seed, seed+1, ...")
    end subroutine test_sweep_seeds

    subroutine test_output_file(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('outfile', "&output file = '' /", [character(len=24) :: "&output file", "a file path"], &
                            error)
    end subroutine test_output_file

    subroutine test_duplicate_group(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('dup', "&grid nx = 32 / &load mean_pressure_pa = 1e4 / &grid nx = 64 /", &
                            [character(len=24) :: "&grid", "given twice", "line 1"], error)
    end subroutine test_duplicate_group

    subroutine test_text_outside(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('outside', "&grid nx = 32 /"//new_line('a')//"nx: 64"//new_line('a'), &
                            [character(len=32) :: "text outside any namelist group", "line 2", "nx:"], error)
        if (allocated(error)) return
        call expect_message('yaml', "grid:"//new_line('a')//"  nx: 64"//new_line('a'), &
                            [character(len=32) :: "text outside any namelist group", "line 1"], error)
    end subroutine test_text_outside

    subroutine test_binary(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('binary', "&grid nx = 32 /"//achar(0)//achar(7), &
                            [character(len=24) :: "not a text file"], error)
    end subroutine test_binary

    subroutine test_no_group(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('nogroup', "! only a comment"//new_line('a'), &
                            [character(len=32) :: "no namelist group found"], error)
    end subroutine test_no_group

    !> k_cut left at its default follows a grid too small for 64: half the grid's Nyquist (four
    !> cells per shortest wavelength); 64 where the grid resolves it; a k_cut given is kept
    subroutine test_default_kcut(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        call read_text('defkcut', "&grid nx = 64, ny = 64 /", cfg, error); if (allocated(error)) return
        call check(error, cfg%surface%k_cut, 16.0_dp, "64^2: half of Nyquist 32"); if (allocated(error)) return
        call read_text('defkcut', "&grid nx = 128, ny = 128 /", cfg, error); if (allocated(error)) return
        call check(error, cfg%surface%k_cut, 32.0_dp, "128^2: Nyquist 64, which 64 does not lie below")
        if (allocated(error)) return
        call read_text('defkcut', "&grid nx = 130, ny = 130 /", cfg, error); if (allocated(error)) return
        call check(error, cfg%surface%k_cut, 64.0_dp, "130^2: 64 is below Nyquist 65"); if (allocated(error)) return
        call read_text('defkcut', "&grid nx = 64, ny = 64 / &surface k_cut = 20 /", cfg, error)
        if (allocated(error)) return
        call check(error, cfg%surface%k_cut, 20.0_dp, "a given k_cut"); if (allocated(error)) return
        call expect_message('defkcut', "&grid nx = 8, ny = 8 / &surface k_roll = 5 /", &
                            [character(len=40) :: "&surface k_roll = 5", "k_cut defaults to half of it"], error)
    end subroutine test_default_kcut

    !> Without &output file the result of NAME.nml is NAME.h5 in the current directory
    subroutine test_default_output(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        character(len=:), allocatable :: stem
        call read_text('defout', "&grid nx = 64, ny = 64 /", cfg, error); if (allocated(error)) return
        stem = unique_name('defout')
        call check(error, cfg%output%file == stem(index(stem, '/', back=.true.) + 1:)//'.h5', &
                   "default output: "//cfg%output%file); if (allocated(error)) return
        call read_text('defout', "&output file = 'x/y.h5' /", cfg, error); if (allocated(error)) return
        call check(error, cfg%output%file == 'x/y.h5', "a given &output file")
    end subroutine test_default_output

    !> &sweep temperatures_c without a &material shift: refused with the values given
    subroutine test_temperatures_without_shift(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('tnoshift', "&material model = 'one_term' / &sweep temperatures_c = 20, 40 /", &
                            [character(len=48) :: "&sweep temperatures_c = 20.0000, 40.0000 is out of range", &
                             "only with a &material shift"], error)
    end subroutine test_temperatures_without_shift

    subroutine test_warnings(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        call read_text('warn', "&grid nx = 32, ny = 32 / &surface k_cut = 8 / &motion speed_m_s = 0.5 /"// &
                       " &sweep speeds_m_s = 0.1, 1.0, alphas_deg = 0, 45 /", cfg, error)
        if (allocated(error)) return
        call check(error, size(cfg%warnings) == 3, "three warnings (elastic sweep, isotropic angles, speed replaced)")
        if (allocated(error)) return
        call check(error, index(cfg%warnings(1)%text, "elastic") > 0 .and. index(cfg%warnings(2)%text, "isotropic") &
                   > 0 .and. index(cfg%warnings(3)%text, "replaced") > 0, "warning texts")
    end subroutine test_warnings

    subroutine test_type_error(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('type1', "&grid nx = 'abc' /", [character(len=24) :: "&grid nx = 'abc'", "an integer"], &
                            error)
        if (allocated(error)) return
        call expect_message('type2', "&grid ny = 32, nx = 32.5 /", [character(len=24) :: "&grid nx = 32.5", &
                            "an integer"], error)
        if (allocated(error)) return
        call expect_message('type3', "&output fields = maybe /", [character(len=24) :: "&output fields = maybe", &
                            "a logical"], error)
        if (allocated(error)) return
        call expect_message('type4', "&grid nz = 4 /", [character(len=32) :: "&grid nz", "no such variable", &
                            "nx, ny, lx_m, ly_m"], error)
    end subroutine test_type_error

    !> A value of the wrong type on a line of its own (a group over several lines, a comment
    !> after it) is named in one line without the comment
    subroutine test_type_error_lines(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        type(error_t), allocatable :: e
        character(len=*), parameter :: nl = new_line('a')
        call read_text('lines', "&grid"//nl//"  nx = 64,"//nl//"  ny = abc,  ! rows"//nl//"  lx_m = 0.01"//nl//"/", &
                       cfg, e)
        call expect_words(e, [character(len=40) :: "&grid ny = abc cannot be read: an integer"], error)
        if (allocated(error)) return
        call check(error, index(e%message, nl) == 0 .and. index(e%message, '!') == 0, &
                   "the message is one line without the comment: "//e%message)
    end subroutine test_type_error_lines

    !> A choice whose text runs past the longest name is refused, not cut to a valid name (a
    !> valid name padded to the old buffers' length and followed by more text was accepted)
    subroutine test_overlong_choices(error)
        type(error_t), allocatable, intent(out) :: error
        character(len=*), parameter :: pad = repeat(' ', 40)//"x'"
        call expect_message('long1', "&solver method = 'pdr"//pad//" /", [character(len=16) :: "&solver method"], error)
        if (allocated(error)) return
        call expect_message('long2', "&solver fft_planner = 'estimate"//pad//" /", &
                            [character(len=20) :: "&solver fft_planner"], error)
        if (allocated(error)) return
        call expect_message('long3', "&solver device = 'cpu"//pad//" /", [character(len=16) :: "&solver device"], error)
        if (allocated(error)) return
        call expect_message('long4', "&solver kernel = 'spectral"//pad//" /", [character(len=16) :: "&solver kernel"], &
                            error)
        if (allocated(error)) return
        call expect_message('long5', "&surface kind = 'flat"//pad//" /", [character(len=16) :: "&surface kind"], error)
        if (allocated(error)) return
        call expect_message('long6', "&surface scale_to = 'expected"//pad//" /", &
                            [character(len=20) :: "&surface scale_to"], error)
        if (allocated(error)) return
        call expect_message('long7', "&material model = 'elastic"//pad//" /", [character(len=16) :: "&material model"], &
                            error)
        if (allocated(error)) return
        call expect_message('long8', "&solver method = '"//repeat('p', 1100)//"' /", &
                            [character(len=40) :: "&solver method is longer than 1023"], error)
        if (allocated(error)) return
        ! blanks that run past the buffer before more text: the read alone would keep 'pdr'
        call expect_message('long9', "&solver method = 'pdr"//repeat(' ', 1030)//"x' /", &
                            [character(len=40) :: "&solver method is longer than 1023"], error)
        if (allocated(error)) return
        call expect_message('long10', "&surface kind = 'file', file = 'a"//repeat(' ', 1030)//"b.h5' /", &
                            [character(len=40) :: "&surface file is longer than 1023"], error)
    end subroutine test_overlong_choices

    !> A shift law needs its constants and a reference; constants of another law, a temperature
    !> where WLF diverges and an unknown law are refused; without a test temperature the
    !> reference's is taken
    subroutine test_material_shift(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        character(len=*), parameter :: m = "&material model = 'one_term', "
        call expect_message('s1', m//"shift = 'wlf', reference_temperature_c = 20 /", &
                            [character(len=40) :: "&material wlf_c1 is needed with shift = 'wlf'"], error)
        if (allocated(error)) return
        call expect_message('s2', m//"shift = 'wlf', reference_temperature_c = 20, wlf_c1 = 17.44, "// &
                            "wlf_c2_k = 51.6, temperature_c = -40 /", &
                            [character(len=40) :: "&material temperature_c", "-31.6"], error)
        if (allocated(error)) return
        call expect_message('s3', m//"shift = 'arrhenius', reference_temperature_c = 20, wlf_c1 = 17.44, "// &
                            "activation_energy_j_mol = 1e5 /", &
                            [character(len=56) :: "&material wlf_c1 has no use with shift = 'arrhenius'"], error)
        if (allocated(error)) return
        call expect_message('s4', m//"temperature_c = 30 /", &
                            [character(len=40) :: "temperature_c has no use with shift = 'none'"], error)
        if (allocated(error)) return
        call expect_message('s5', m//"shift = 'vft' /", [character(len=40) :: "&material shift", "arrhenius"], error)
        if (allocated(error)) return
        ! just above WLF's divergence a_T overflows (log10 a_T > 308): refused, not a kernel of NaN
        call expect_message('s7', m//"shift = 'wlf', reference_temperature_c = 20, wlf_c1 = 17.44, "// &
                            "wlf_c2_k = 51.6, temperature_c = -31.5 /", &
                            [character(len=40) :: "&material temperature_c = -31.5", "a_T = "], error)
        if (allocated(error)) return
        call expect_message('s8', m//"shift = 'wlf', reference_temperature_c = 20, wlf_c1 = 17.44, "// &
                            "wlf_c2_k = 51.6 / &sweep temperatures_c = 20, -31.5 /", &
                            [character(len=40) :: "&sweep temperatures_c(2) = -31.5"], error)
        if (allocated(error)) return
        call read_text('s6', m//"shift = 'arrhenius', reference_temperature_c = 20, activation_energy_j_mol = 1e5 /", &
                       cfg, error)
        if (allocated(error)) return
        call check(error, cfg%material%temperature_c == 20.0_dp, "the test temperature defaults to the reference")
        if (allocated(error)) return
        ! a test temperature the sweep replaces, a base without a layer: one warning each
        call read_text('s9', m//"shift = 'arrhenius', reference_temperature_c = 20, activation_energy_j_mol = 1e5,"// &
                       " temperature_c = 30, base = 'frictionless' / &sweep temperatures_c = 20, 40 /", cfg, error)
        if (allocated(error)) return
        call check(error, size(cfg%warnings) == 2, "two warnings"); if (allocated(error)) return
        call check(error, index(cfg%warnings(1)%text, "replaced by the &sweep temperatures_c") > 0 .and. &
                   index(cfg%warnings(2)%text, "the solid is a half-space") > 0, "the warnings' texts")
    end subroutine test_material_shift

    !> shift = 'table': its two lists read; refused in one line naming the variable: a table of
    !> one point or of two lengths, temperatures not increasing, log10 a_T not decreasing, a
    !> temperature of the material or of the sweep outside it, a WLF constant with it, the lists
    !> with another law; a time shifted beyond 1e200 s
    subroutine test_material_shift_table(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        character(len=*), parameter :: m = "&material model = 'one_term', shift = 'table', "// &
                                           "reference_temperature_c = 20, "
        character(len=*), parameter :: tab = "shift_temperatures_c = 0, 20, 40, shift_log10_at = 2, 0, -1.5"
        call read_text('t1', m//"temperature_c = 30, "//tab//" / &sweep temperatures_c = 0, 40 /", cfg, error)
        if (allocated(error)) return
        call check(error, size(cfg%material%shift_table_c) == 3 .and. cfg%material%shift_table_log10(3) == -1.5_dp &
                   .and. cfg%material%temperature_c == 30.0_dp, "the table read"); if (allocated(error)) return
        call expect_message('t2', m//"shift_temperatures_c = 20, shift_log10_at = 0 /", [character(len=80) :: &
                            "&material shift_temperatures_c and shift_log10_at must list the same number (2 to 256)", &
                            "got 1 and 1"], error)
        if (allocated(error)) return
        call expect_message('t3', m//"shift_temperatures_c = 0, 20, 40, shift_log10_at = 2, 0 /", &
                            [character(len=40) :: "got 3 and 2"], error)
        if (allocated(error)) return
        call expect_message('t4', m//"shift_temperatures_c = 0, 20, 20, shift_log10_at = 2, 0, -1 /", &
                            [character(len=64) :: "&material shift_temperatures_c(3) = 20", "strictly increasing"], error)
        if (allocated(error)) return
        call expect_message('t5', m//"shift_temperatures_c = 0, 20, 40, shift_log10_at = 2, 0, 0.5 /", &
                            [character(len=64) :: "&material shift_log10_at(3) = 0.5", &
                            "a_T falls as the temperature rises"], error)
        if (allocated(error)) return
        call expect_message('t6', m//"temperature_c = 41, "//tab//" /", [character(len=64) :: &
                            "&material temperature_c = 41", "within the shift table", "0 to 40", &
                            "not extrapolated"], error)
        if (allocated(error)) return
        call expect_message('t7', "&material model = 'one_term', shift = 'table', reference_temperature_c = -5, "// &
                            tab//" /", [character(len=64) :: "&material reference_temperature_c = -5", &
                            "within the shift table"], error)
        if (allocated(error)) return
        call expect_message('t8', m//tab//" / &sweep temperatures_c = 10, 60 /", [character(len=64) :: &
                            "&sweep temperatures_c(2) = 60", "within the &material shift table"], error)
        if (allocated(error)) return
        call expect_message('t9', m//tab//", wlf_c1 = 8.86 /", [character(len=64) :: &
                            "&material wlf_c1 has no use with shift = 'table'"], error)
        if (allocated(error)) return
        call expect_message('t10', "&material model = 'one_term', shift = 'arrhenius', reference_temperature_c = 20,"// &
                            " activation_energy_j_mol = 1e5, "//tab//" /", [character(len=64) :: &
                            "&material shift_temperatures_c has no use with shift = 'arrhenius'"], error)
        if (allocated(error)) return
        call expect_message('t11', "&material model = 'one_term', tau_s = 1e199, shift = 'table', "// &
                            "reference_temperature_c = 20, temperature_c = 0, "//tab//" /", [character(len=64) :: &
                            "&material temperature_c = 0", "beyond 1e-300 to 1e200 s"], error)
    end subroutine test_material_shift_table

    !> A relaxation series of 256 terms, times 1e-20..1e180 s (the most terms and about the
    !> longest times &material takes), is read; a 257th term is refused
    subroutine test_material_long_series(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        character(len=:), allocatable :: e, t
        character(len=32) :: w
        integer :: j
        e = ''; t = ''
        do j = 1, 256
            write (w, '(es24.16)') 10.0_dp**(-20.0_dp + 200.0_dp*(j - 1)/255.0_dp)
            t = t//trim(adjustl(w))//", "
            e = e//"1e6, "
        end do
        call read_text('long', "&material model = 'relaxation', e0_pa = 1e6, relax_e_pa = "//e//" relax_rho_s = "// &
                       t//" /", cfg, error)
        if (allocated(error)) return
        call check(error, size(cfg%material%prony_time_s) == 256, "256 terms read"); if (allocated(error)) return
        call check(error, cfg%material%prony_time_s(256), 1.0e180_dp, "the last time", rel=1.0e-14_dp)
        if (allocated(error)) return
        call expect_message('long2', "&material model = 'relaxation', e0_pa = 1e6, relax_e_pa = "//e//"1e6, "// &
                            "relax_rho_s = "//t//"1e181 /", [character(len=40) :: "&material relax_e_pa = 1e6, 1e6", &
                            "(257 values)", "a list of up to 256 real numbers"], error)
    end subroutine test_material_long_series

    subroutine test_grid_absurd(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('absurd1', "&grid lx_m = 1e300 /", [character(len=24) :: "&grid lx_m", "1e-9 to 1e3"], error)
        if (allocated(error)) return
        call expect_message('absurd2', "&grid lx_m = 1e-300 /", [character(len=24) :: "&grid lx_m", "1e-9 to 1e3"], error)
    end subroutine test_grid_absurd

    subroutine test_material_infinite(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('inf', "&material model='creep', e0_pa=1e6, creep_c_per_pa=1e-7, creep_tau_s=Infinity /", &
                            [character(len=24) :: "&material creep_tau_s", "not finite"], error)
    end subroutine test_material_infinite

    subroutine test_sweep_range_no_n(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('rangenon', "&sweep speed_min_m_s = 1e-3, speed_max_m_s = 10 /", &
                            [character(len=40) :: "&sweep speed_min_m_s/speed_max_m_s need n_speeds"], error)
    end subroutine test_sweep_range_no_n

    subroutine test_sweep_gap(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('gap', "&sweep speeds_m_s(1) = 0.1, speeds_m_s(3) = 1.0 /", &
                            [character(len=24) :: "&sweep speeds_m_s", "has a gap"], error)
    end subroutine test_sweep_gap

    !> The most negative double is a value like any other (refused here as a negative speed), not
    !> a marker of an unset entry
    subroutine test_sweep_sentinel(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('sentinel', "&sweep speeds_m_s = 0.1, -1.7976931348623157e308 /", &
                            [character(len=24) :: "&sweep speeds_m_s(2)", "0 to 1e12"], error)
    end subroutine test_sweep_sentinel

    subroutine test_output_long(error)
        type(error_t), allocatable, intent(out) :: error
        call expect_message('long', "&output file = '"//repeat('a', 1100)//".h5' /", &
                            [character(len=32) :: "&output file", "longer than 1023 characters"], error)
    end subroutine test_output_long

end module test_veslide_config
