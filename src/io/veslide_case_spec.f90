!> The specification of a case, resolved once from the configuration that was read: the one place
!> where namelist values become what the numerics take (degrees to radians, the material's times
!> shifted to its temperature, method and device names to ids). The configuration is only read
!> here; a study asks for the material at each of its temperatures (`resolve_material`) and sets
!> the other swept values on copies of the specification (veslide_study).
module veslide_case_spec
    use veslide_kinds, only: dp, radians
    use veslide_error, only: error_t, add_context
    use veslide_config, only: config_t, case_law
    use veslide_config_material, only: material_config_t
    use veslide_material, only: new_elastic, new_one_term, new_creep, new_relaxation, shift_factor, &
                                BASE_BONDED, BASE_FRICTIONLESS
    use veslide_kernel, only: kernel_variant_id
    use veslide_solver_options, only: solver_method_id, device_choice_id
    use veslide_case_data, only: case_spec_t, material_spec_t
    implicit none
    private
    public :: case_spec_of, resolve_material

contains

    !> The specification of the case `cfg` describes (a study's first case: its single values)
    subroutine case_spec_of(cfg, spec, error)
        type(config_t), intent(in) :: cfg
        type(case_spec_t), intent(out) :: spec
        type(error_t), allocatable, intent(out) :: error
        spec%input_path = cfg%path
        spec%input_text = cfg%text
        spec%nx = cfg%grid%nx; spec%ny = cfg%grid%ny
        spec%lx_m = cfg%grid%lx_m; spec%ly_m = cfg%grid%ly_m
        associate (s => cfg%surface, o => spec%surface)
            o%kind = s%kind; o%seed = s%seed
            o%hurst = s%hurst; o%eccentricity = s%eccentricity; o%alpha_rad = radians(s%alpha_deg)
            o%k_low = s%k_low; o%k_roll = s%k_roll; o%k_cut = s%k_cut
            o%rms_slope = s%rms_slope; o%rms_height_m = s%rms_height_m
            o%realised = s%scale_to == 'realised'
            o%amplitude_m = s%amplitude_m; o%wavelength_m = s%wavelength_m
            o%direction_rad = radians(s%direction_deg); o%radius_m = s%radius_m
            o%file = s%file; o%dataset = s%dataset; o%preparation = s%preparation
            o%edge_jump = s%edge_jump; o%edge_step = s%edge_step
            o%filled_fraction = s%filled_fraction; o%band_slope_removed = s%band_slope_removed
        end associate
        allocate (spec%warnings(0))
        if (allocated(cfg%warnings)) spec%warnings = cfg%warnings
        spec%speed_m_s = cfg%motion%speed_m_s
        spec%direction_deg = cfg%motion%direction_deg
        spec%mean_pressure_pa = cfg%load%mean_pressure_pa
        spec%approach_m = cfg%load%approach_m
        spec%shear_coefficient = cfg%interface%shear_coefficient
        spec%law = case_law(cfg)
        associate (s => cfg%solver, o => spec%solver)
            o%method = solver_method_id(s%method)
            o%device = device_choice_id(s%device)
            o%tolerance = s%tolerance
            o%max_iterations = s%max_iterations
            o%anderson_memory = s%anderson_memory
            o%balance_every = s%balance_every
            o%balance_ratio = s%balance_ratio
            o%balance_factor = s%balance_factor
            spec%kernel_variant = kernel_variant_id(s%kernel)
            spec%alias_tol = s%alias_tol; spec%alias_max = s%alias_max
            spec%fft_planner = s%fft_planner
            spec%threads = s%threads
        end associate
        associate (a => cfg%analysis, o => spec%analysis)
            o%anisotropy = a%anisotropy; o%zeta1 = a%zeta1; o%zeta2 = a%zeta2; o%n_theta = a%n_theta
            o%iso_tol = a%iso_tol; o%patches = a%patches; o%persson = a%persson
            o%persson_correction = a%persson_correction
        end associate
        spec%fields = cfg%output%fields
        call resolve_material(cfg%material, cfg%material%temperature_c, spec%material, error)
        call add_context(error, "veslide: "//cfg%path//": &material: ")
    end subroutine case_spec_of

    !> The solid of &material at `temperature_c`: the master curve's times multiplied by the shift
    !> factor a_T there (1 without a shift), a layer on its base when a thickness is given
    subroutine resolve_material(m, temperature_c, out, error)
        type(material_config_t), intent(in) :: m
        real(dp), intent(in) :: temperature_c
        type(material_spec_t), intent(out) :: out
        type(error_t), allocatable, intent(out) :: error
        real(dp) :: a
        out%model = m%model
        out%shifted = m%shift /= 'none'
        out%temperature_c = temperature_c
        a = shift_factor(m%shift, temperature_c, m%reference_temperature_c, m%wlf_c1, m%wlf_c2_k, &
                         m%activation_energy_j_mol, m%shift_table_c, m%shift_table_log10)
        out%shift_factor = a
        select case (m%model)
        case ('elastic')
            call new_elastic(out%solid, m%young_pa, m%poisson, error)
        case ('one_term')
            call new_one_term(out%solid, m%einf_pa, m%ratio, a*m%tau_s, m%poisson, error)
        case ('creep')
            call new_creep(out%solid, m%e0_pa, m%prony_coef, a*m%prony_time_s, m%poisson, error)
        case ('relaxation')
            call new_relaxation(out%solid, m%e0_pa, m%prony_coef, a*m%prony_time_s, m%poisson, error)
        end select
        if (.not. allocated(error) .and. m%thickness_m > 0.0_dp) then
            out%solid%thickness_m = m%thickness_m
            out%solid%base = merge(BASE_BONDED, BASE_FRICTIONLESS, m%base == 'bonded')
        end if
    end subroutine resolve_material

end module veslide_case_spec
