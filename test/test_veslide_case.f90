!> One case end to end: the output contract (paths, units, types), the results list (names unique,
!> units everywhere, the same values as the file), and refusals that name the input
module test_veslide_case
    use veslide_kinds, only: dp, i8, pi
    use veslide_strings, only: str
    use veslide_material, only: layer_factor, BASE_BONDED, BASE_FRICTIONLESS
    use veslide_error, only: fatal_error
    use veslide_config, only: config_t
    use veslide_hdf5, only: h5file_t
    use veslide_output, only: prepare_output, release_output, commit_output
    use veslide_quantities, only: results_t, case_results, field_names, field_units, field_layout, &
                                  case_field
    use veslide_case, only: case_t, run_case, case_grid, build_surface, build_kernel
    use veslide_case_data, only: case_spec_t
    use veslide_case_spec, only: case_spec_of
    use veslide_memory, only: memory_estimate_bytes
    use veslide_contact, only: contact_problem_t, new_contact_problem_moving
    use veslide_solver, only: auto_method, planned_methods
    use veslide_solver_options, only: SOLVER_AUTO, SOLVER_PDR, SOLVER_DR
    use veslide_case_file, only: write_case
    use testsuite, only: error_t, unittest_t, new_unittest, check, report
    use test_support, only: unique_name
    use test_veslide_config, only: read_text
    implicit none
    private
    public :: collect_case

contains

    subroutine collect_case(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("hdf5-contract", test_hdf5_contract), &
            new_unittest("results-named-once-with-units", test_results_list), &
            new_unittest("friction-sign-and-lateral-direction", test_friction_sign), &
            new_unittest("persson-equals-the-solve-in-full-contact", test_persson_full_contact), &
            new_unittest("approach-is-hertz-plus-the-lattice-term", test_approach_hertz), &
            new_unittest("temperature-is-a-speed-scale", test_temperature_superposition), &
            new_unittest("layer-single-wave-in-full-contact", test_layer_single_wave), &
            new_unittest("layer-thick-is-the-half-space", test_layer_thick), &
            new_unittest("specification-resolved-from-the-input", test_spec_resolved), &
            new_unittest("memory-sized-for-the-method-auto-runs", test_memory_auto_rule), &
            new_unittest("fields-written-as-catalogued", test_field_catalogue), &
            new_unittest("shear-incompressible-adds-mu-f-only", test_shear_incompressible), &
            new_unittest("shear-single-wave-in-full-contact", test_shear_single_wave), &
            new_unittest("shear-persson-equals-the-solve-in-full-contact", test_shear_persson) &
            ]
    end subroutine collect_case

    !> A small case end to end: the paths and units of the output contract
    subroutine test_hdf5_contract(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        type(case_t) :: c
        type(h5file_t) :: f
        character(len=:), allocatable :: out, tmp
        character(len=40) :: paths(12)
        real(dp) :: a
        integer(i8) :: its
        integer :: k, u, lock
        out = unique_name('contract.h5')
        call read_text('contract', "&grid nx = 32, ny = 32 / &surface k_cut = 8 / &solver fft_planner='estimate' /"// &
                       " &output file = '"//out//"' / &analysis anisotropy = .true., patches = .true. /", cfg, error)
        if (allocated(error)) return
        call prepare_output(cfg%output%file, .false., tmp, lock, error); if (allocated(error)) return
        call run_case(cfg, c, error); if (allocated(error)) return
        call write_case(tmp, c, error); if (allocated(error)) return
        call commit_output(tmp, out, .false., error); if (allocated(error)) return
        call release_output(lock, out)
        paths = [character(len=40) :: '/scalars/contact_area_fraction', '/scalars/mean_separation_m', &
                 '/scalars/rms_height_m', '/scalars/max_pressure_pa', '/scalars/iterations', '/scalars/converged', &
                 '/scalars/residual', '/fields/height_m', '/fields/pressure_pa', '/fields/displacement_m', &
                 '/fields/gap_m', '/anisotropy/surface_tensor']
        call f%open(out, 'r', error); if (allocated(error)) return
        do k = 1, size(paths)
            if (.not. f%exists(trim(paths(k)))) then
                call fatal_error(error, "missing "//trim(paths(k))); return
            end if
            if (.not. f%attr_exists(trim(paths(k)), 'units')) then
                call fatal_error(error, "no units on "//trim(paths(k))); return
            end if
        end do
        call f%read_r0('/scalars/contact_area_fraction_cells', a, error); if (allocated(error)) return
        call f%read_i0('/scalars/iterations', its, error); if (allocated(error)) return
        call f%close()
        open (newunit=u, file=out); close (u, status='delete')
        call check(error, a, real(count(c%state%p > 0), dp)/1024.0_dp, "area read back", rel=0.0_dp)
        if (allocated(error)) return
        call check(error, its == c%state%iterations, "iterations stored as an integer")
    end subroutine test_hdf5_contract

    !> Every scalar has one name and a units string; the list the summary reads is the file's
    subroutine test_results_list(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        type(case_t) :: c
        type(results_t) :: r
        integer :: i, j
        call read_text('results', "&grid nx = 16, ny = 16 / &surface k_cut = 4 / &solver fft_planner='estimate' /"// &
                       " &material model='one_term' / &motion speed_m_s = 0.1 /"// &
                       " &analysis anisotropy = .true., patches = .true. /", cfg, error)
        if (allocated(error)) return
        call run_case(cfg, c, error); if (allocated(error)) return
        call case_results(c, r)
        do i = 1, r%n
            call check(error, len(r%scalars(i)%units) > 0, r%scalars(i)%name//" has no units")
            if (allocated(error)) return
            do j = i + 1, r%n
                call check(error, r%scalars(i)%name /= r%scalars(j)%name, r%scalars(i)%name//" defined twice")
                if (allocated(error)) return
            end do
        end do
        call check(error, r%has('friction_coefficient') .and. r%has('gamma_d') .and. r%has('patch_count'), &
                   "quantities missing")
    end subroutine test_results_list

    !> Sliding along +y over an anisotropic surface: friction positive (it resists the motion),
    !> the lateral force is the component 90 degrees counter-clockwise from v (here along -x)
    subroutine test_friction_sign(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        type(case_t) :: c
        type(results_t) :: r
        call read_text('sign', "&grid nx = 32, ny = 32 / &surface k_cut = 8, eccentricity = 0.4, alpha_deg = 30 /"// &
                       " &solver fft_planner='estimate' / &material model='one_term' /"// &
                       " &motion speed_m_s = 0.05, direction_deg = 90 /", cfg, error)
        if (allocated(error)) return
        call run_case(cfg, c, error); if (allocated(error)) return
        call case_results(c, r)
        call check(error, r%get('friction_coefficient') > 0.0_dp, "friction must resist the motion")
        if (allocated(error)) return
        call check(error, r%get('friction_coefficient'), -c%force_pa(2)/cfg%load%mean_pressure_pa, "friction = -F_y/p", &
                   rel=1.0e-14_dp)
        if (allocated(error)) return
        call check(error, r%get('lateral_force_ratio'), -c%force_pa(1)/cfg%load%mean_pressure_pa, &
                   "lateral = F.(z x v_hat)/p = -F_x/p", rel=1.0e-14_dp)
    end subroutine test_friction_sign

    !> &analysis persson beside a solve: in full contact the theory is exact, so its friction and
    !> lateral force equal the boundary elements' (anisotropic surface, oblique v), and its area is 1
    subroutine test_persson_full_contact(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        type(case_t) :: c
        type(results_t) :: r
        real(dp) :: f_half
        integer :: k
        ! the half-space, then a bonded layer (q0 d = 1): the theory uses the layered kernel
        do k = 1, 2
            call read_text('persson', "&grid nx = 32, ny = 32 / &surface k_cut = 8, eccentricity = 0.5, alpha_deg = 30 /"// &
                           " &solver fft_planner='estimate', tolerance = 1e-12 / &material model='one_term'"// &
                           trim(merge("                      ", ", thickness_m = 1.6e-3", k == 1))//" /"// &
                           " &load mean_pressure_pa = 3e7 / &motion speed_m_s = 0.05, direction_deg = 20 /"// &
                           " &analysis persson = .true. /", cfg, error)
            if (allocated(error)) return
            call run_case(cfg, c, error); if (allocated(error)) return
            call case_results(c, r)
            call check(error, r%get('contact_area_fraction'), 1.0_dp, "full contact", abs=0.0_dp)
            if (allocated(error)) return
            call check(error, r%get('persson_contact_area_fraction'), 1.0_dp, "theory: full contact", abs=1.0e-12_dp)
            if (allocated(error)) return
            call check(error, r%get('persson_friction_coefficient'), r%get('friction_coefficient'), "friction", &
                       rel=1.0e-9_dp)
            if (allocated(error)) return
            call check(error, r%get('persson_lateral_force_ratio'), r%get('lateral_force_ratio'), "lateral force", &
                       rel=1.0e-8_dp)
            if (allocated(error)) return
            if (k == 1) f_half = r%get('friction_coefficient')
        end do
        call check(error, abs(r%get('friction_coefficient')/f_half - 1.0_dp) > 1.0e-2_dp, "the layer changed nothing")
    end subroutine test_persson_full_contact

    !> approach_m is the rigid-body approach since first contact (docs/input.md conventions): for a
    !> paraboloid of radius R under a force F = p L^2 with a << L it is Hertz's a^2/R plus the
    !> displacement of the periodic images at the apex with the mean displacement zero,
    !> F Z/(pi E* L), Z = 4 zeta(1/2) beta(1/2) = -3.90026... (the square lattice's sum of 1/|m|
    !> less its integral; beta: Dirichlet's), and the images' curvature there, which raises 1/R
    !> by F S3/(2 pi E* L^3), S3 = 4 zeta(3/2) beta(3/2), and so multiplies a^2/R by
    !> 1 + (2 S3/(9 pi)) (a/L)^3 (4e-5 and 1.3e-4 here). Measured on 256^2: within 7e-4 at
    !> a/L = 0.04 and 0.06; it grows with the load (before, approach_m was the mean gap, which falls).
    subroutine test_approach_hertz(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp), parameter :: lattice = -3.900264920001956_dp
        !> sum of 1/|n|^3 over the square lattice's points but the origin, 4 zeta(3/2) beta(3/2)
        real(dp), parameter :: s3 = 9.033621683100950_dp
        real(dp), parameter :: l = 0.01_dp, radius = 0.1_dp, estar = 1.0e6_dp/0.75_dp
        real(dp), parameter :: loads(2) = [10.0_dp, 43.4_dp]
        type(config_t) :: cfg
        type(case_t) :: c
        type(results_t) :: r
        real(dp) :: f, a, expected, approach(2)
        character(len=16) :: text
        integer :: k
        do k = 1, 2
            write (text, '(f0.1)') loads(k)
            call read_text('approach', "&grid nx = 256, ny = 256, lx_m = 0.01 / &surface kind = 'paraboloid', "// &
                           "radius_m = 0.1 / &material young_pa = 1.0e6, poisson = 0.5 / &load mean_pressure_pa = "// &
                           trim(text)//" / &solver fft_planner = 'estimate' / &output fields = .false. /", cfg, error)
            if (allocated(error)) return
            call run_case(cfg, c, error); if (allocated(error)) return
            call case_results(c, r)
            f = loads(k)*l**2
            a = (3.0_dp*f*radius/(4.0_dp*estar))**(1.0_dp/3.0_dp)
            ! the images' curvature at the contact multiplies a^2/R by 1 + (2 S3/(9 pi)) (a/L)^3
            expected = a**2/radius*(1.0_dp + 2.0_dp*s3/(9.0_dp*pi)*(a/l)**3) + f*lattice/(pi*estar*l)
            approach(k) = r%get('approach_m')
            call check(error, approach(k), expected, "approach against Hertz with the lattice term", rel=2.0e-3_dp)
            if (allocated(error)) return
        end do
        call check(error, approach(2) > approach(1), "the approach grows with the load")
    end subroutine test_approach_hertz

    !> Time-temperature superposition: the material at T slides at v as the master curve at
    !> T_ref slides at a_T v (E*(w, T) = E*(a_T w, T_ref)); WLF with the universal constants at
    !> T - T_ref = 10 K: log10 a_T = -17.44*10/61.6, and Arrhenius (E_a = 100 kJ/mol, 20 -> 40 C):
    !> ln a_T = (E_a/R)(1/313.15 - 1/293.15); the output records T and a_T
    subroutine test_temperature_superposition(error)
        type(error_t), allocatable, intent(out) :: error
        character(len=*), parameter :: base = "&grid nx = 32, ny = 32 / &surface k_cut = 8 / &solver fft_planner"// &
            " = 'estimate', tolerance = 1e-12 / &output fields = .false. / &material model = 'creep', e0_pa = 1e6,"// &
            " creep_c_per_pa = 4e-7, 4e-7, creep_tau_s = 1e-3, 1e-1, "
        real(dp), parameter :: r_gas = 8.314462618_dp
        real(dp) :: a_wlf, a_arr
        a_wlf = 10.0_dp**(-17.44_dp*10.0_dp/61.6_dp)
        a_arr = exp(1.0e5_dp/r_gas*(1.0_dp/313.15_dp - 1.0_dp/293.15_dp))
        call same_as_speed("shift = 'wlf', reference_temperature_c = 20, temperature_c = 30, wlf_c1 = 17.44,"// &
                           " wlf_c2_k = 51.6 /", a_wlf, error)
        if (allocated(error)) return
        call same_as_speed("shift = 'arrhenius', reference_temperature_c = 20, temperature_c = 40,"// &
                           " activation_energy_j_mol = 1e5 /", a_arr, error)
    contains
        subroutine same_as_speed(shift, a, error)
            character(len=*), intent(in) :: shift
            real(dp), intent(in) :: a
            type(error_t), allocatable, intent(out) :: error
            type(config_t) :: cfg
            type(case_t) :: c
            type(results_t) :: r
            real(dp) :: f_t, area_t, a_out
            character(len=32) :: v
            call read_text('tts1', base//shift//" &motion speed_m_s = 0.1 /", cfg, error); if (allocated(error)) return
            call run_case(cfg, c, error); if (allocated(error)) return
            call case_results(c, r)
            f_t = r%get('friction_coefficient'); area_t = r%get('contact_area_fraction'); a_out = r%get('shift_factor')
            call check(error, a_out, a, "shift factor recorded", rel=1.0e-14_dp); if (allocated(error)) return
            write (v, '(es24.17)') 0.1_dp*a
            call read_text('tts2', base//"/ &motion speed_m_s = "//trim(v)//" /", cfg, error)
            if (allocated(error)) return
            call run_case(cfg, c, error); if (allocated(error)) return
            call case_results(c, r)
            call check(error, f_t, r%get('friction_coefficient'), "friction at T against a_T v at T_ref", rel=1.0e-9_dp)
            if (allocated(error)) return
            call check(error, area_t, r%get('contact_area_fraction'), "area at T against a_T v at T_ref", rel=1.0e-9_dp)
        end subroutine same_as_speed
    end subroutine test_temperature_superposition

    !> A single wave in full contact on a layer: the pressure is H/K mode by mode, so friction and
    !> lateral force are the half-space's divided by S(q d) (q d = 0.7, a wave at 30 degrees to
    !> v: both force components; bonded with nu = 1/2, frictionless with nu = 0.3)
    subroutine test_layer_single_wave(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp), parameter :: q = 2.0_dp*2.0_dp*pi/0.01_dp, t = 0.7_dp
        call one("bonded", 0.5_dp, BASE_BONDED, error); if (allocated(error)) return
        call one("frictionless", 0.3_dp, BASE_FRICTIONLESS, error)
    contains
        subroutine one(base, nu, id, error)
            character(len=*), intent(in) :: base
            real(dp), intent(in) :: nu
            integer, intent(in) :: id
            type(error_t), allocatable, intent(out) :: error
            type(config_t) :: cfg
            type(case_t) :: c
            type(results_t) :: r
            real(dp) :: f0, l0, s
            character(len=64) :: text
            character(len=:), allocatable :: base_text
            base_text = "&grid nx = 32, ny = 32, lx_m = 0.01 / &surface kind = 'cosine', amplitude_m = 1e-7,"// &
                " wavelength_m = 0.005, direction_deg = 0 / &load mean_pressure_pa = 1e6 / &motion speed_m_s = 0.1,"// &
                " direction_deg = 30 / &solver fft_planner = 'estimate', tolerance = 1e-12 / &output fields = .false. /"
            call read_text('wave0', base_text//" &material model = 'one_term', poisson = "//str(nu)//" /", cfg, error)
            if (allocated(error)) return
            call run_case(cfg, c, error); if (allocated(error)) return
            call case_results(c, r)
            call check(error, r%get('contact_area_fraction'), 1.0_dp, "full contact", abs=0.0_dp); if (allocated(error)) return
            f0 = r%get('friction_coefficient'); l0 = r%get('lateral_force_ratio')
            write (text, '(es24.17)') t/q
            call read_text('wave1', base_text//" &material model = 'one_term', poisson = "//str(nu)// &
                           ", thickness_m = "//trim(text)//", base = '"//base//"' /", cfg, error)
            if (allocated(error)) return
            call run_case(cfg, c, error); if (allocated(error)) return
            call case_results(c, r)
            s = layer_factor(t, nu, id)
            call report(base//": friction, rel. error", abs(r%get('friction_coefficient')*s/f0 - 1.0_dp))
            call report(base//": lateral, rel. error", abs(r%get('lateral_force_ratio')*s/l0 - 1.0_dp))
            call check(error, r%get('friction_coefficient'), f0/s, base//": friction = half-space/S", rel=1.0e-12_dp)
            if (allocated(error)) return
            call check(error, r%get('lateral_force_ratio'), l0/s, base//": lateral force = half-space/S", rel=1.0e-12_dp)
            if (allocated(error)) return
            call check(error, abs(l0) > 1.0e-3_dp*abs(f0), base//": the lateral force is not zero")
        end subroutine one
    end subroutine test_layer_single_wave

    !> A layer with q d >= 20 for every mode of the scene (q0 d = 20) is the half-space to 1e-12
    subroutine test_layer_thick(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        type(case_t) :: c
        type(results_t) :: r
        real(dp) :: a0, f0, g0
        character(len=*), parameter :: base = "&grid nx = 32, ny = 32, lx_m = 0.01 / &surface k_cut = 8 /"// &
            " &motion speed_m_s = 0.1 / &solver fft_planner = 'estimate',"// &
            " tolerance = 1e-12 / &output fields = .false. /"
        call read_text('thick0', base//" &material model = 'one_term' /", cfg, error); if (allocated(error)) return
        call run_case(cfg, c, error); if (allocated(error)) return
        call case_results(c, r)
        a0 = r%get('contact_area_fraction'); f0 = r%get('friction_coefficient'); g0 = r%get('mean_separation_m')
        call read_text('thick1', base//" &material model = 'one_term', thickness_m = 0.031830988618379 /", cfg, error)
        if (allocated(error)) return
        call run_case(cfg, c, error); if (allocated(error)) return
        call case_results(c, r)
        call report("area, rel. difference", abs(r%get('contact_area_fraction')/a0 - 1.0_dp))
        call report("friction, rel. difference", abs(r%get('friction_coefficient')/f0 - 1.0_dp))
        call report("mean separation, rel. difference", abs(r%get('mean_separation_m')/g0 - 1.0_dp))
        call check(error, r%get('contact_area_fraction'), a0, "area", rel=1.0e-12_dp); if (allocated(error)) return
        call check(error, r%get('friction_coefficient'), f0, "friction", rel=1.0e-12_dp); if (allocated(error)) return
        call check(error, r%get('mean_separation_m'), g0, "mean separation", rel=1.0e-12_dp)
    end subroutine test_layer_thick


    !> The specification holds the input in SI units and radians, the solid at its temperature
    !> (times multiplied by a_T), the velocity from speed and direction, and the solver's ids
    subroutine test_spec_resolved(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        type(case_spec_t) :: spec
        real(dp) :: a, v(2)
        call read_text('spec', "&grid nx = 32, ny = 16, lx_m = 0.02 / &surface alpha_deg = 30, eccentricity = 0.5, k_cut = 4 /"// &
            " &material model = 'one_term', tau_s = 0.01, shift = 'wlf', temperature_c = 30,"// &
            " reference_temperature_c = 20, wlf_c1 = 8.86, wlf_c2_k = 101.6 / &motion speed_m_s = 0.2,"// &
            " direction_deg = 60 / &solver method = 'pdr', kernel = 'galerkin' /", cfg, error)
        if (allocated(error)) return
        call case_spec_of(cfg, spec, error); if (allocated(error)) return
        a = 10.0_dp**(-8.86_dp*10.0_dp/(101.6_dp + 10.0_dp))
        v = 0.2_dp*[cos(pi/3), sin(pi/3)]
        call check(error, spec%nx == 32 .and. spec%ny == 16 .and. spec%lx_m == 0.02_dp .and. spec%ly_m == 0.01_dp, &
                   "the grid"); if (allocated(error)) return
        call check(error, spec%surface%alpha_rad, pi/6, "alpha in radians", rel=1.0e-15_dp); if (allocated(error)) return
        call check(error, spec%material%shift_factor, a, "the WLF shift factor", rel=1.0e-13_dp)
        if (allocated(error)) return
        call check(error, spec%material%solid%time_s(1), a*0.01_dp, "tau shifted to 30 C", rel=1.0e-13_dp)
        if (allocated(error)) return
        call check(error, norm2(spec%velocity() - v) <= 1.0e-15_dp*0.2_dp, "the velocity vector")
        if (allocated(error)) return
        call check(error, spec%solver%method == SOLVER_PDR .and. spec%kernel_name() == 'galerkin', "method and kernel")
    end subroutine test_spec_resolved

    !> 'auto' is sized for the method the solver module will run: on 256^2 a viscoelastic solid
    !> whose Einf/E0 keeps the operator's spread under the threshold runs pdr and is sized as pdr;
    !> one with Einf/E0 = 1000 may run dr (it does at this speed) and is sized for the larger of
    !> the two; an elastic solid runs bccg
    subroutine test_memory_auto_rule(error)
        type(error_t), allocatable, intent(out) :: error
        character(len=*), parameter :: scene = "&grid nx = 256, ny = 256 / &surface k_cut = 8 /"// &
            " &motion speed_m_s = 0.05 / &solver fft_planner = 'estimate', method = '"
        type(config_t) :: cfg
        type(case_spec_t) :: spec
        type(case_t) :: c
        type(contact_problem_t) :: problem
        integer(i8) :: auto_b, named(3)
        integer, allocatable :: planned(:)
        integer :: k, ran
        character(len=*), parameter :: solids(3) = [character(len=60) :: &
            "&material model = 'one_term', ratio = 11 /", "&material model = 'one_term', ratio = 1000 /", &
            "&material model = 'elastic' /"]
        character(len=4), parameter :: methods(3) = ['pdr ', 'dr  ', 'bccg']
        do k = 1, 3
            call read_text('memrule', scene//trim(methods(k))//"' / "//trim(solids(k)), cfg, error)
            if (allocated(error)) return
            call case_spec_of(cfg, spec, error); if (allocated(error)) return
            named(k) = memory_estimate_bytes(spec)
            call read_text('memrule', scene//"auto' / "//trim(solids(k)), cfg, error); if (allocated(error)) return
            call case_spec_of(cfg, spec, error); if (allocated(error)) return
            auto_b = memory_estimate_bytes(spec)
            ! the method auto takes once the kernel is built is among those it was sized for
            c%spec = spec
            call case_grid(spec, c%grid, error); if (allocated(error)) return
            call build_surface(spec, c%h, error); if (allocated(error)) return
            call build_kernel(spec, c%grid, c%kernel, c%kernel_seconds, error); if (allocated(error)) return
            call new_contact_problem_moving(problem, c%kernel, c%h, spec%mean_pressure_pa, error)
            if (allocated(error)) return
            ran = auto_method(problem)
            call problem%release(c%kernel, c%h)
            planned = planned_methods(SOLVER_AUTO, .not. (k < 3), c%grid%cells(), &
                                      spec%material%solid%einf_pa/spec%material%solid%e0_pa)
            call check(error, any(planned == ran), "auto ran a method it was not sized for")
            if (allocated(error)) return
            if (k == 2) then
                call check(error, ran == SOLVER_DR .and. auto_b >= named(1) .and. auto_b >= named(2), &
                           "Einf/E0 = 1000: not sized for the larger of pdr and dr")
            else
                call check(error, auto_b == named(k), "auto not sized as "//trim(methods(k)))
            end if
            if (allocated(error)) return
        end do
        call check(error, named(2) > named(1), "dr (Anderson history) needs more than pdr")
        if (allocated(error)) return
        ! a layer's factor varies across a shell of |q|: Einf/E0 = 19.5 no longer bounds the spread
        ! (a thin bonded layer at 1 m/s runs dr), so auto is sized for the larger of pdr and dr
        call read_text('memrule', "&grid nx = 256, ny = 256 / &surface k_cut = 8 / &motion speed_m_s = 1 /"// &
            " &solver fft_planner = 'estimate' / &material model = 'one_term', ratio = 19.5,"// &
            " thickness_m = 5e-5, base = 'bonded' /", cfg, error)
        if (allocated(error)) return
        call case_spec_of(cfg, spec, error); if (allocated(error)) return
        call check(error, memory_estimate_bytes(spec) >= named(2), "a viscoelastic layer not sized for dr")
    end subroutine test_memory_auto_rule

    !> /fields holds the catalogue's fields, each with its units and layout, shaped (nx, ny)
    subroutine test_field_catalogue(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        type(case_t), target :: c
        type(h5file_t) :: f
        character(len=:), allocatable :: out, units, layout
        real(dp) :: x(16, 8)
        integer :: k, u
        out = unique_name('catalogue.h5')
        call read_text('catalogue', "&grid nx = 16, ny = 8 / &surface k_cut = 4 / &solver fft_planner='estimate' /", &
                       cfg, error)
        if (allocated(error)) return
        call run_case(cfg, c, error); if (allocated(error)) return
        call write_case(out, c, error); if (allocated(error)) return
        call f%open(out, 'r', error); if (allocated(error)) return
        do k = 1, size(field_names)
            associate (name => '/fields/'//trim(field_names(k)))
                call check(error, f%exists(name), "missing "//name); if (allocated(error)) exit
                call f%read_attr_text(name, 'units', units, error); if (allocated(error)) exit
                call f%read_attr_text(name, 'layout', layout, error); if (allocated(error)) exit
                call f%read_r2(name, x, error); if (allocated(error)) exit
                call check(error, units == trim(field_units(k)) .and. layout == field_layout .and. &
                           all(x == case_field(c, k)), "field "//name//" is not as catalogued")
                if (allocated(error)) exit
            end associate
        end do
        call f%close()
        open (newunit=u, file=out); close (u, status='delete')
    end subroutine test_field_catalogue

    !> &interface shear_coefficient on an incompressible solid (nu = 1/2, beta = 0): the normal
    !> problem is the one without shear (pressure, gap and area to 1e-12; the kernel is the same
    !> bit for bit, so they are equal), and the friction coefficient is the one without shear plus
    !> mu_f <p>/p0 = mu_f (1e-9: <p> is p0 to the load error). A rough surface in partial contact
    !> under a one-term solid sliding at 20 degrees; the lateral force is unchanged.
    subroutine test_shear_incompressible(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp), parameter :: mu_f = 0.6_dp
        type(config_t) :: cfg
        type(case_t) :: c0, c1
        type(results_t) :: r0, r1
        character(len=*), parameter :: base = "&grid nx = 32, ny = 32 / &surface k_cut = 8, eccentricity = 0.5 /"// &
            " &solver fft_planner = 'estimate', tolerance = 1e-12 / &material model = 'one_term', poisson = 0.5 /"// &
            " &motion speed_m_s = 0.05, direction_deg = 20 / &output fields = .false. /"
        call read_text('shear0', base, cfg, error); if (allocated(error)) return
        call run_case(cfg, c0, error); if (allocated(error)) return
        call case_results(c0, r0)
        call read_text('shear1', base//" &interface shear_coefficient = 0.6 /", cfg, error); if (allocated(error)) return
        call run_case(cfg, c1, error); if (allocated(error)) return
        call case_results(c1, r1)
        call check(error, r0%get('contact_area_fraction') < 0.5_dp, "partial contact"); if (allocated(error)) return
        call report("pressure, max difference/max", maxval(abs(c1%state%p - c0%state%p))/maxval(c0%state%p))
        call check(error, maxval(abs(c1%state%p - c0%state%p)) <= 1.0e-12_dp*maxval(c0%state%p), "pressure")
        if (allocated(error)) return
        call check(error, maxval(abs(c1%state%g - c0%state%g)) <= 1.0e-12_dp*maxval(c0%state%g), "gap")
        if (allocated(error)) return
        call check(error, r1%get('contact_area_fraction'), r0%get('contact_area_fraction'), "area", rel=1.0e-12_dp)
        if (allocated(error)) return
        call check(error, r1%get('mean_separation_m'), r0%get('mean_separation_m'), "mean gap", rel=1.0e-12_dp)
        if (allocated(error)) return
        call report("friction - (without shear + mu_f)", r1%get('friction_coefficient') - &
                    (r0%get('friction_coefficient') + mu_f))
        call check(error, r1%get('friction_coefficient'), r0%get('friction_coefficient') + mu_f, &
                   "friction = hysteresis + mu_f", abs=1.0e-9_dp)
        if (allocated(error)) return
        call check(error, r1%get('friction_hysteresis'), r0%get('friction_coefficient'), "the hysteresis part", &
                   rel=1.0e-12_dp)
        if (allocated(error)) return
        call check(error, r1%get('friction_interfacial'), mu_f, "the interfacial part", abs=1.0e-9_dp)
        if (allocated(error)) return
        call check(error, r1%get('lateral_force_ratio'), r0%get('lateral_force_ratio'), "lateral force", rel=1.0e-12_dp)
        if (allocated(error)) return
        call check(error, r1%get('shear_coefficient') == mu_f .and. .not. r0%has('shear_coefficient') .and. &
                   .not. r0%has('friction_hysteresis'), "the shear and the parts recorded only with shear")
    end subroutine test_shear_incompressible

    !> A single wave h0 cos(q.x) in full contact under a shear mu_f p v_hat (docs/interface.md):
    !> the gap is 0, so w = h (less the approach) and p(q) = h(q)/K(q) with
    !> K = 2 (1 - nu^2) C(-q.v) (1 - i a)/|q|, a = beta mu_f (q.v_hat)/|q|. For an elastic solid
    !>   p - p0 = (E* |q| h0/2) (cos q.x - a sin q.x)/(1 + a^2),
    !>   F = <p grad h> = q E* |q| h0^2 a/(4 (1 + a^2)),
    !>   friction_hysteresis = -F.v_hat/p0 = -E* |q|^2 h0^2 beta mu_f s^2/(4 p0 (1 + a^2)) < 0,
    !> s = (q.v_hat)/|q|: the pressure shifts to the trailing flank by atan(a) and pushes the wave
    !> along v, and the friction coefficient is that plus mu_f. In general (a solid in motion)
    !> F = (h0^2/2) q Im(1/K), the same for a = 0 (no shear). Cases: nu = 0.3, mu_f = 0.5; a wave
    !> along x with v along x (s = 1) and at 30 degrees (s = cos 30: a lateral force), a wave at
    !> 45 degrees with v along x, and a one-term solid (nu = 0.2, mu_f = 0.8) at 0.1 m/s at 30
    !> degrees. Pressure within 1e-12 of the amplitude |h0/K| (3e-12 in motion), forces within
    !> 1e-12 relative (solver tolerance 1e-13, its smallest; measured 1.5e-13 elastic, 8.7e-13 in
    !> motion, and 2e-14 at most).
    subroutine test_shear_single_wave(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp), parameter :: l = 0.01_dp, h0 = 1.0e-6_dp, p0 = 1.0e5_dp
        call one(0.0_dp, 2.0_dp, 0.0_dp, .false., error); if (allocated(error)) return
        call one(0.0_dp, 2.0_dp, 30.0_dp, .false., error); if (allocated(error)) return
        call one(45.0_dp, 2.0_dp*sqrt(2.0_dp), 0.0_dp, .false., error); if (allocated(error)) return
        call one(0.0_dp, 2.0_dp, 30.0_dp, .true., error)
    contains
        !> a wave at `wave_deg` of `waves` wavelengths per cell side's length, v at `v_deg`
        subroutine one(wave_deg, waves, v_deg, moving, error)
            real(dp), intent(in) :: wave_deg, waves, v_deg
            logical, intent(in) :: moving
            type(error_t), allocatable, intent(out) :: error
            type(config_t) :: cfg
            type(case_t) :: c
            type(results_t) :: r
            real(dp) :: nu, mu_f, beta, q(2), vhat(2), lat(2), s, a, estar, amp, x(2), worst, hyst, f(2)
            complex(dp) :: kq
            character(len=32) :: wl, wd, vd
            character(len=:), allocatable :: material, tag
            integer :: i, j
            if (moving) then
                nu = 0.2_dp; mu_f = 0.8_dp
                material = "&material model = 'one_term', poisson = 0.2 / &interface shear_coefficient = 0.8 /"// &
                           " &motion speed_m_s = 0.1, "
            else
                nu = 0.3_dp; mu_f = 0.5_dp
                material = "&material young_pa = 1e7, poisson = 0.3 / &interface shear_coefficient = 0.5 /"// &
                           " &motion "
            end if
            write (wl, '(es24.17)') l/waves; write (wd, '(es24.17)') wave_deg; write (vd, '(es24.17)') v_deg
            tag = "wave "//str(nint(wave_deg))//" deg, v "//str(nint(v_deg))//" deg"// &
                  trim(merge(", moving", "        ", moving))
            call read_text('shearwave', "&grid nx = 32, ny = 32, lx_m = 0.01 / &surface kind = 'cosine',"// &
                           " amplitude_m = 1e-6, wavelength_m = "//trim(wl)//", direction_deg = "//trim(wd)//" /"// &
                           " &load mean_pressure_pa = 1e5 / &solver fft_planner = 'estimate', tolerance = 1e-13 /"// &
                           " &output fields = .false. / "//material//"direction_deg = "//trim(vd)//" /", cfg, error)
            if (allocated(error)) return
            call run_case(cfg, c, error); if (allocated(error)) return
            call case_results(c, r)
            call check(error, r%get('contact_area_fraction'), 1.0_dp, tag//": full contact", abs=0.0_dp)
            if (allocated(error)) return
            beta = (1.0_dp - 2.0_dp*nu)/(2.0_dp*(1.0_dp - nu))
            q = 2.0_dp*pi*waves/l*[cos(wave_deg*pi/180), sin(wave_deg*pi/180)]
            vhat = [cos(v_deg*pi/180), sin(v_deg*pi/180)]; lat = [-vhat(2), vhat(1)]
            s = dot_product(q, vhat)/norm2(q); a = beta*mu_f*s
            ! the kernel of mode q, written anew: K = 2 (1 - nu^2) C(-q.v) (1 - i a)/|q|
            kq = 2.0_dp*(1.0_dp - nu**2)*c%spec%material%solid%compliance(-dot_product(q, c%spec%velocity())) &
                 *cmplx(1.0_dp, -a, dp)/norm2(q)
            estar = 1.0e7_dp/(1.0_dp - nu**2)
            amp = 0.5_dp*estar*norm2(q)*h0
            worst = 0.0_dp
            do j = 1, 32
                do i = 1, 32
                    x = [(i - 1)*l/32, (j - 1)*l/32]
                    if (moving) then
                        worst = max(worst, abs(c%state%p(i, j) - p0 - real(h0/kq*exp(cmplx(0.0_dp, &
                                    dot_product(q, x), dp)), dp))/abs(h0/kq))
                    else
                        worst = max(worst, abs(c%state%p(i, j) - p0 - amp*(cos(dot_product(q, x)) - &
                                    a*sin(dot_product(q, x)))/(1.0_dp + a*a))/amp)
                    end if
                end do
            end do
            call report(tag//": pressure, max error/amplitude", worst)
            ! (the solver's residual, 1e-13 of h_rms, on the grid's shortest modes is a pressure 1/K
            ! times larger, |q_max|/|q| = 8 here: 3e-12 for the solid in motion, whose solver stops
            ! with less to spare)
            call check(error, worst <= merge(3.0e-12_dp, 1.0e-12_dp, moving), &
                       tag//": the pressure is not the closed form")
            if (allocated(error)) return
            if (moving) then
                f = 0.5_dp*h0**2*q*aimag(1.0_dp/kq)
            else
                f = q*estar*norm2(q)*h0**2*a/(4.0_dp*(1.0_dp + a*a))
                ! the expanded form of -F.v_hat/p0 (the sign: negative for an elastic solid)
                hyst = -estar*dot_product(q, q)*h0**2*beta*mu_f*s*s/(4.0_dp*p0*(1.0_dp + a*a))
                call check(error, -dot_product(f, vhat)/p0, hyst, tag//": the closed form's two writings", &
                           rel=1.0e-14_dp)
                if (allocated(error)) return
            end if
            call report(tag//": friction_hysteresis, rel. error", &
                        abs(r%get('friction_hysteresis')/(-dot_product(f, vhat)/p0) - 1.0_dp))
            call check(error, r%get('friction_hysteresis'), -dot_product(f, vhat)/p0, tag//": friction_hysteresis", &
                       rel=1.0e-12_dp)
            if (allocated(error)) return
            call check(error, r%get('friction_coefficient'), -dot_product(f, vhat)/p0 + mu_f, &
                       tag//": friction = hysteresis + mu_f", abs=1.0e-9_dp)
            if (allocated(error)) return
            call check(error, r%get('friction_interfacial'), mu_f, tag//": friction_interfacial", abs=1.0e-9_dp)
            if (allocated(error)) return
            call check(error, r%get('lateral_force_ratio'), dot_product(f, lat)/p0, tag//": lateral force", &
                       rel=1.0e-12_dp, abs=1.0e-12_dp*norm2(f)/p0)
            if (allocated(error)) return
            call check(error, r%get('force_x_pa'), f(1) - mu_f*p0*vhat(1), tag//": force along x", &
                       rel=1.0e-12_dp, abs=1.0e-12_dp*mu_f*p0)
            if (allocated(error)) return
            call check(error, .not. c%kernel%symmetric .and. c%state%method /= 'bccg', &
                       tag//": a non-symmetric kernel and a solver for it")
            if (allocated(error)) return
        end subroutine one
    end subroutine test_shear_single_wave

    !> &analysis persson with shear: the theory takes the coupled kernel, and in full contact it is
    !> exact, so its friction (with mu_f added) and lateral force equal the solve's (nu = 0.3,
    !> anisotropic surface, oblique v); also on an elastic solid at rest, where only the shear's
    !> direction says which way is forward
    subroutine test_shear_persson(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        type(case_t) :: c
        type(results_t) :: r
        integer :: k
        do k = 1, 2
            call read_text('spersson', "&grid nx = 32, ny = 32 / &surface k_cut = 8, eccentricity = 0.5, alpha_deg"// &
                           " = 30 / &solver fft_planner='estimate', tolerance = 1e-12 / &load mean_pressure_pa = 3e7 /"// &
                           " &interface shear_coefficient = 0.4 / &analysis persson = .true. / "// &
                           trim(merge("&material model='one_term', poisson = 0.3 / &motion speed_m_s = 0.05,", &
                                      "&material young_pa = 1e8, poisson = 0.3 / &motion                    ", k == 1))// &
                           " direction_deg = 20 /", cfg, error)
            if (allocated(error)) return
            call run_case(cfg, c, error); if (allocated(error)) return
            call case_results(c, r)
            call check(error, r%get('contact_area_fraction'), 1.0_dp, "full contact", abs=0.0_dp)
            if (allocated(error)) return
            call check(error, r%get('persson_friction_coefficient'), r%get('friction_coefficient'), "friction", &
                       rel=1.0e-9_dp)
            if (allocated(error)) return
            call check(error, r%get('persson_lateral_force_ratio'), r%get('lateral_force_ratio'), "lateral force", &
                       rel=1.0e-8_dp)
            if (allocated(error)) return
            call check(error, abs(r%get('friction_hysteresis')) > 1.0e-6_dp, "a hysteresis part")
            if (allocated(error)) return
        end do
    end subroutine test_shear_persson

end module test_veslide_case
