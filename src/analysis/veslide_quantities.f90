!> The named results of a case, each defined once with its units: the list that the HDF5 case
!> group (/scalars, /anisotropy, /patches), the /summary row of a study, the ensemble statistics
!> and the printed summary all read.
!>
!> A scalar is a `quantity_t` (name, units, value, integer or real, axial angle or not); arrays
!> (tensors, polar samples) are `array_t`. The catalogue of a case is `case_results`, in output
!> order; the definitions of derived quantities live here too, as procedures that append to a
!> `results_t` list: forces and friction (`add_force_quantities`), the solver report
!> (`add_solver_quantities`). A new output scalar is one `add` line in `case_results`.
!>
!> The 2-D fields of a case have a catalogue of their own (`field_names`, `field_units`,
!> `field_layout`, and `case_field` for the array of each): the HDF5 writer loops over it, and
!> the Python reader lists what the file's /fields group holds.
module veslide_quantities
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use veslide_kinds, only: dp, pi, radians
    use veslide_contact_law, only: ADH_ENERGY, ADH_RANGE, ADH_STRESS
    use veslide_contact, only: contact_state_t
    use veslide_case_data, only: case_t
    use veslide_fields, only: field_rms, field_max, field_mean, field_count
    use veslide_collective, only: global_max
    use veslide_system, only: peak_memory_bytes
    use veslide_analysis, only: contact_area_fraction, contact_area_subcell, mean_separation
    use veslide_anisotropy, only: m2_of_theta
    use veslide_warning, only: WARNS_NEVER
    implicit none
    private
    public :: quantity_t, array_t, results_t, add_force_quantities, add_solver_quantities, axial_of
    public :: case_results, field_names, field_units, field_layout, case_field
    public :: AXIAL_NONE, AXIAL_HALF_TURN, AXIAL_SYMMETRIC

    !> How an angle averages over seeds: not an angle, an axis in [0, pi), an axis in (-pi/2, pi/2]
    integer, parameter :: AXIAL_NONE = 0, AXIAL_HALF_TURN = 1, AXIAL_SYMMETRIC = 2

    !> The fields of a case, in the order they are written under /fields: the name (the HDF5
    !> dataset's), its units; `case_field` gives the array of each
    character(len=*), parameter :: field_names(4) = [character(len=14) :: 'height_m', 'pressure_pa', &
                                                     'displacement_m', 'gap_m']
    character(len=*), parameter :: field_units(4) = [character(len=2) :: 'm', 'Pa', 'm', 'm']
    !> How a 2-D field is laid out, for readers in other languages (each field's `layout` attribute)
    character(len=*), parameter :: field_layout = "Fortran order (nx, ny): h5py shape (ny, nx), index [iy, ix]"

    type :: quantity_t
        character(len=:), allocatable :: name    !! HDF5 name under /scalars and /summary column
        character(len=:), allocatable :: units   !! SI units ('-' for none)
        real(dp) :: value = 0.0_dp
        logical :: is_integer = .false.          !! stored as a 64-bit integer
        integer :: axial = AXIAL_NONE            !! AXIAL_* : how it averages over seeds
        !> where the case's file keeps it: 'scalars' (/scalars/NAME) or 'validity' (/validity/NAME,
        !> with its threshold and when it warns, veslide_warning's WARNS_*)
        character(len=:), allocatable :: group
        real(dp) :: threshold = 0.0_dp
        integer :: warns = WARNS_NEVER
    end type quantity_t

    type :: array_t
        character(len=:), allocatable :: path    !! HDF5 path below the case group, e.g. '/anisotropy/theta_rad'
        character(len=:), allocatable :: units
        character(len=:), allocatable :: layout  !! 'layout' attribute ('' for none)
        real(dp), allocatable :: values(:)
    end type array_t

    type :: results_t
        type(quantity_t), allocatable :: scalars(:)
        type(array_t), allocatable :: arrays(:)
        integer :: n = 0, na = 0
    contains
        procedure :: add => results_add
        procedure :: add_array => results_add_array
        procedure :: get => results_get
        procedure :: has => results_has
        procedure :: trim => results_trim
    end type results_t

contains

    !> Append a scalar
    pure subroutine results_add(self, name, value, units, is_integer, axial, group, threshold, warns)
        class(results_t), intent(inout) :: self
        character(len=*), intent(in) :: name, units
        real(dp), intent(in) :: value
        logical, intent(in), optional :: is_integer
        integer, intent(in), optional :: axial
        character(len=*), intent(in), optional :: group      !! 'scalars' (default) or 'validity'
        real(dp), intent(in), optional :: threshold          !! a validity measure's
        integer, intent(in), optional :: warns               !! WARNS_* (default WARNS_NEVER)
        type(quantity_t), allocatable :: tmp(:)
        if (.not. allocated(self%scalars)) allocate (self%scalars(16))
        if (self%n == size(self%scalars)) then
            allocate (tmp(2*self%n)); tmp(1:self%n) = self%scalars
            call move_alloc(tmp, self%scalars)
        end if
        self%n = self%n + 1
        associate (q => self%scalars(self%n))
            q%name = name; q%units = units; q%value = value
            q%is_integer = .false.; if (present(is_integer)) q%is_integer = is_integer
            q%axial = axial_of(name); if (present(axial)) q%axial = axial
            q%group = 'scalars'; if (present(group)) q%group = group
            q%threshold = 0.0_dp; if (present(threshold)) q%threshold = threshold
            q%warns = WARNS_NEVER; if (present(warns)) q%warns = warns
        end associate
    end subroutine results_add

    !> Append an array under `path` (below the case group)
    pure subroutine results_add_array(self, path, values, units, layout)
        class(results_t), intent(inout) :: self
        character(len=*), intent(in) :: path, units
        real(dp), intent(in) :: values(:)
        character(len=*), intent(in), optional :: layout
        type(array_t), allocatable :: tmp(:)
        if (.not. allocated(self%arrays)) allocate (self%arrays(8))
        if (self%na == size(self%arrays)) then
            allocate (tmp(2*self%na)); tmp(1:self%na) = self%arrays
            call move_alloc(tmp, self%arrays)
        end if
        self%na = self%na + 1
        associate (a => self%arrays(self%na))
            a%path = path; a%units = units; a%values = values
            a%layout = ''; if (present(layout)) a%layout = layout
        end associate
    end subroutine results_add_array

    !> How the quantity `name` averages over seeds: the directions of axes are angles modulo pi,
    !> theta in [0, pi) (of the slope tensors and of the patches), phi of eq. (16) in (-pi/2, pi/2]
    pure integer function axial_of(name) result(axial)
        character(len=*), intent(in) :: name
        axial = AXIAL_NONE
        select case (name)
        case ('theta_s_rad', 'theta_d_rad', 'patch_theta_rad')
            axial = AXIAL_HALF_TURN
        case ('phi_rad')
            axial = AXIAL_SYMMETRIC
        end select
    end function axial_of

    !> Value of the scalar `name` (huge() when absent; see `has`)
    pure real(dp) function results_get(self, name) result(v)
        class(results_t), intent(in) :: self
        character(len=*), intent(in) :: name
        integer :: k
        v = huge(1.0_dp)
        do k = 1, self%n
            if (self%scalars(k)%name == name) then
                v = self%scalars(k)%value; return
            end if
        end do
    end function results_get

    pure logical function results_has(self, name) result(yes)
        class(results_t), intent(in) :: self
        character(len=*), intent(in) :: name
        integer :: k
        yes = .false.
        do k = 1, self%n
            if (self%scalars(k)%name == name) yes = .true.
        end do
    end function results_has

    !> Shrink the lists to their lengths (scalars(1:n), arrays(1:na))
    pure subroutine results_trim(self)
        class(results_t), intent(inout) :: self
        if (.not. allocated(self%scalars)) allocate (self%scalars(0))
        if (.not. allocated(self%arrays)) allocate (self%arrays(0))
        self%scalars = self%scalars(1:self%n)
        self%arrays = self%arrays(1:self%na)
    end subroutine results_trim

    !> Forces of the solid on the rigid surface per unit nominal area, and what follows from them:
    !>   friction_force_pa = -F.v_hat, friction_coefficient = -F.v_hat/p_mean (> 0 against the motion),
    !>   lateral_force_pa = F.(z_hat x v_hat), lateral_force_ratio = F.(z_hat x v_hat)/p_mean,
    !>   force_x_pa, force_y_pa, friction_coefficient_slope = -<p grad h>.v_hat/p_mean (the check
    !>   estimator) and dissipated_power_w_m2 = -F.v.
    !> v_hat is the direction `direction_deg` of v (also at v = 0, where all vanish without shear).
    !> F = `force_pa` (<p grad w>, the normal traction on the tilted surface: the hysteresis part)
    !> minus `interfacial_pa` v_hat (mu_f <p>, a full-slip Coulomb shear's); with that part (> 0)
    !> the friction, the forces, the slope estimator and the power are the totals, and
    !> friction_hysteresis and friction_interfacial are the two parts of the friction coefficient.
    !> The lateral force is the hysteresis part's alone: the shear is along v_hat.
    pure subroutine add_force_quantities(r, force_pa, slope_force_pa, velocity_m_s, direction_deg, p_mean, &
                                         interfacial_pa)
        type(results_t), intent(inout) :: r
        real(dp), intent(in) :: force_pa(2), slope_force_pa(2), velocity_m_s(2), direction_deg, p_mean
        !> mu_f <p> [Pa] (absent or 0: no interfacial shear, and every value as without it)
        real(dp), intent(in), optional :: interfacial_pa
        real(dp) :: vhat(2), lat(2), fi, f(2)
        fi = 0.0_dp; if (present(interfacial_pa)) fi = interfacial_pa
        vhat = [cos(radians(direction_deg)), sin(radians(direction_deg))]
        lat = [-vhat(2), vhat(1)]
        if (fi > 0.0_dp) then
            f = force_pa - fi*vhat
            call r%add('friction_force_pa', -dot_product(force_pa, vhat) + fi, 'Pa')
            call r%add('friction_coefficient', ratio(-dot_product(force_pa, vhat) + fi), '-')
            call r%add('friction_hysteresis', ratio(-dot_product(force_pa, vhat)), '-')
            call r%add('friction_interfacial', ratio(fi), '-')
        else
            f = force_pa
            call r%add('friction_force_pa', -dot_product(force_pa, vhat), 'Pa')
            call r%add('friction_coefficient', ratio(-dot_product(force_pa, vhat)), '-')
        end if
        call r%add('lateral_force_pa', dot_product(force_pa, lat), 'Pa')
        call r%add('lateral_force_ratio', ratio(dot_product(force_pa, lat)), '-')
        call r%add('force_x_pa', f(1), 'Pa')
        call r%add('force_y_pa', f(2), 'Pa')
        if (fi > 0.0_dp) then
            call r%add('friction_coefficient_slope', ratio(-dot_product(slope_force_pa, vhat) + fi), '-')
        else
            call r%add('friction_coefficient_slope', ratio(-dot_product(slope_force_pa, vhat)), '-')
        end if
        call r%add('dissipated_power_w_m2', -dot_product(f, velocity_m_s), 'W/m^2')
    contains
        !> A force over the load: NaN at a zero or tensile load (an adhesive law's), where no
        !> coefficient of friction is defined
        pure real(dp) function ratio(x) result(y)
            real(dp), intent(in) :: x
            if (p_mean > 0.0_dp) then
                y = x/p_mean
            else
                y = ieee_value(1.0_dp, ieee_quiet_nan)
            end if
        end function ratio
    end subroutine add_force_quantities

    !> An adhesive law's parameters and what it did: the mean over the nominal area of the
    !> tensile traction (the adhesive force per area, pulling) and of the compressive one (their
    !> difference is the load), and the area under a tension larger than the solution's error
    !> (docs/adhesion.md): the residual bounds |p + sigma(g)| on the open cells, in units of the
    !> pressure scale, so where the attraction is below it (Dugdale's beyond its range, where it
    !> is 0; the exponential law's far out) the sign of p is round-off and the cell not counted
    subroutine add_adhesion_quantities(r, c)
        type(results_t), intent(inout) :: r
        type(case_t), intent(in) :: c
        real(dp) :: err
        ! (the error: the tolerance, or the residual where the solve did not reach it; at most
        ! the pressure scale)
        err = c%spec%solver%tolerance
        if (c%state%residual > err) err = min(c%state%residual, 1.0_dp)
        associate (law => c%spec%law)
            call r%add('adhesion_energy_j_m2', law%param(ADH_ENERGY), 'J/m^2')
            call r%add('adhesion_range_m', law%param(ADH_RANGE), 'm')
            call r%add('adhesion_stress_pa', law%param(ADH_STRESS), 'Pa')
        end associate
        call r%add('adhesive_pressure_pa', field_mean(c%grid, max(-c%state%p, 0.0_dp)), 'Pa')
        call r%add('compressive_pressure_pa', field_mean(c%grid, max(c%state%p, 0.0_dp)), 'Pa')
        call r%add('adhesive_area_fraction', &
                   real(field_count(c%grid, c%state%p < -err*c%state%p_scale_pa), dp)/c%grid%cells(), '-')
        call r%add('trailing_edge_energy_j_m2', c%trailing_edge_energy, 'J/m^2')
        call r%add('trailing_edges', real(c%trailing_edges, dp), '-', is_integer=.true.)
        call r%add('leading_edge_energy_j_m2', c%leading_edge_energy, 'J/m^2')
        call r%add('leading_edges', real(c%leading_edges, dp), '-', is_integer=.true.)
    end subroutine add_adhesion_quantities

    !> The solver's report: iterations, work, convergence and the four residual measures
    pure subroutine add_solver_quantities(r, state, tolerance)
        type(results_t), intent(inout) :: r
        type(contact_state_t), intent(in) :: state
        real(dp), intent(in) :: tolerance
        call r%add('iterations', real(state%iterations, dp), '-', is_integer=.true.)
        call r%add('operator_applications', real(state%operator_applications, dp), '-', is_integer=.true.)
        call r%add('converged', merge(1.0_dp, 0.0_dp, state%converged), '-', is_integer=.true.)
        call r%add('residual', state%residual, '-')
        call r%add('penetration', state%penetration, '-')
        call r%add('complementarity', state%complementarity, '-')
        call r%add('negative_pressure', state%negative_pressure, '-')
        call r%add('load_error', state%load_error, '-')
        call r%add('tolerance', tolerance, '-')
    end subroutine add_solver_quantities

    !> The results of a case, in output order: every scalar with its units, and the arrays
    subroutine case_results(c, r)
        type(case_t), intent(in) :: c
        type(results_t), intent(out) :: r
        real(dp) :: along, across, d, peak
        integer :: j, n_warnings
        associate (solid => c%spec%material%solid)
        call r%add('contact_area_fraction', contact_area_subcell(c%state%p, c%state%g, c%grid, c%spec%law), '-')
        call r%add('contact_area_fraction_cells', contact_area_fraction(c%state%p, c%grid, c%spec%law, c%state%g), '-')
        call r%add('mean_separation_m', mean_separation(c%state%g, c%grid), 'm')
        call r%add('rms_height_m', field_rms(c%grid, c%h), 'm')
        call r%add('max_pressure_pa', field_max(c%grid, c%state%p), 'Pa')
        call r%add('mean_pressure_pa', c%spec%mean_pressure_pa, 'Pa')
        if (c%spec%law%adhesive()) call add_adhesion_quantities(r, c)
        ! the rigid-body approach since first contact: g = w - h + D with mean w = 0 gives
        ! D = h_max at first touch and D = h_mean + d under load (d: the solver's mean gap)
        call r%add('approach_m', field_max(c%grid, c%h) - field_mean(c%grid, c%h) - c%state%approach_m, 'm')
        call add_solver_quantities(r, c%state, c%spec%solver%tolerance)
        call r%add('length_x_m', c%grid%lx_m, 'm')
        call r%add('length_y_m', c%grid%ly_m, 'm')
        call r%add('nx', real(c%grid%nx, dp), '-', is_integer=.true.)
        call r%add('ny', real(c%grid%ny, dp), '-', is_integer=.true.)
        call r%add('contact_modulus_pa', solid%e0_pa/(1.0_dp - solid%poisson**2), 'Pa')
        if (solid%thickness_m > 0.0_dp) call r%add('layer_thickness_m', solid%thickness_m, 'm')
        if (c%spec%shear_coefficient > 0.0_dp) call r%add('shear_coefficient', c%spec%shear_coefficient, '-')
        if (c%spec%material%shifted) then
            call r%add('temperature_c', c%spec%material%temperature_c, 'degC')
            call r%add('shift_factor', c%spec%material%shift_factor, '-')
        end if
        call r%add('speed_m_s', norm2(c%spec%velocity()), 'm/s')
        call r%add('velocity_direction_deg', c%spec%direction_deg, 'degree')
        call add_force_quantities(r, c%force_pa, c%slope_force_pa, c%spec%velocity(), c%spec%direction_deg, &
                                  c%spec%mean_pressure_pa, c%interfacial_force_pa)
        call r%add('kernel_alias_error', c%kernel%alias_error, '-')
        call r%add('kernel_alias_zones', real(c%kernel%alias_zones, dp), '-', is_integer=.true.)
        call r%add('kernel_min_re_m_pa', c%kernel%min_re, 'm/Pa')
        peak = real(peak_memory_bytes(), dp)
        call global_max(c%grid, peak)
        call r%add('processes', real(c%grid%ranks, dp), '-', is_integer=.true.)
        call r%add('memory_estimate_bytes', real(c%memory_estimate_bytes, dp), 'B', is_integer=.true.)
        call r%add('memory_peak_bytes', peak, 'B', is_integer=.true.)
        call r%add('surface_seconds', c%surface_seconds, 's')
        call r%add('kernel_seconds', c%kernel_seconds, 's')
        call r%add('solve_seconds', c%solve_seconds, 's')
        if (c%have_anisotropy) then
            call r%add('gamma_s', c%gamma_s, '-'); call r%add('gamma_d', c%gamma_d, '-')
            call r%add('theta_s_rad', c%theta_s, 'rad'); call r%add('theta_d_rad', c%theta_d, 'rad')
            call r%add('sigma1', c%sigma1, '-'); call r%add('sigma2', c%sigma2, '-')
            call r%add('phi_rad', c%phi, 'rad')
            block
                real(dp) :: theta(c%spec%analysis%n_theta)
                theta = [(pi*(j - 1)/c%spec%analysis%n_theta, j = 1, c%spec%analysis%n_theta)]
                call r%add_array('/anisotropy/band_q_per_m', c%band_q, '1/m')
                call r%add_array('/anisotropy/band_zeta', [c%spec%analysis%zeta1, c%spec%analysis%zeta2], '-')
                call r%add_array('/anisotropy/surface_tensor', reshape(c%m_surface, [4]), '-', &
                                 layout='[M11, M21, M12, M22]')
                call r%add_array('/anisotropy/deformed_tensor', reshape(c%m_deformed, [4]), '-', &
                                 layout='[M11, M21, M12, M22]')
                call r%add_array('/anisotropy/theta_rad', theta, 'rad')
                call r%add_array('/anisotropy/m2_surface', m2_of_theta(c%m_surface, theta), '-')
                call r%add_array('/anisotropy/mu2_deformed', m2_of_theta(c%m_deformed, theta), '-')
            end block
        end if
        if (c%have_patches) then
            call r%add('patch_count', real(c%patches%count, dp), '-', is_integer=.true.)
            call r%add('patch_mean_area_fraction', c%patches%mean_area_fraction, '-')
            call r%add('patch_gamma', c%patches%gamma, '-')
            call r%add('patch_theta_rad', c%patches%theta, 'rad')
            call r%add('percolates_x', merge(1.0_dp, 0.0_dp, c%percolates_x), '-', is_integer=.true.)
            call r%add('percolates_y', merge(1.0_dp, 0.0_dp, c%percolates_y), '-', is_integer=.true.)
            ! along and across v when v lies on a grid axis; -1 (undefined) otherwise
            d = modulo(c%spec%direction_deg, 180.0_dp)
            along = -1.0_dp; across = -1.0_dp
            if (d < 1.0e-9_dp .or. d > 180.0_dp - 1.0e-9_dp) then
                along = merge(1.0_dp, 0.0_dp, c%percolates_x); across = merge(1.0_dp, 0.0_dp, c%percolates_y)
            else if (abs(d - 90.0_dp) < 1.0e-9_dp) then
                along = merge(1.0_dp, 0.0_dp, c%percolates_y); across = merge(1.0_dp, 0.0_dp, c%percolates_x)
            end if
            call r%add('percolates_along_v', along, '-', is_integer=.true.)
            call r%add('percolates_across_v', across, '-', is_integer=.true.)
            call r%add_array('/patches/orientation_tensor', reshape(c%patches%orientation, [4]), '-', &
                             layout='[G11, G21, G12, G22]')
        end if
        if (c%have_persson) then
            call r%add('persson_contact_area_fraction', c%persson%contact_area_fraction, '-')
            if (c%spec%shear_coefficient > 0.0_dp) then     ! its part mu_f p0/p0 added, as to friction_coefficient
                call r%add('persson_friction_coefficient', c%persson%friction_coefficient + c%spec%shear_coefficient, &
                           '-')
            else
                call r%add('persson_friction_coefficient', c%persson%friction_coefficient, '-')
            end if
            call r%add('persson_lateral_force_ratio', c%persson%lateral_force_ratio, '-')
            call r%add_array('/persson/q_per_m', c%persson%q_per_m, '1/m')
            call r%add_array('/persson/area_fraction', c%persson%area_fraction, '-')
        end if
        ! its validity: the measures (/validity) and how many warnings it carries
        if (allocated(c%validity)) then
            do j = 1, size(c%validity)
                associate (m => c%validity(j))
                    call r%add(m%name, m%value, m%units, is_integer=m%is_integer, group='validity', &
                               threshold=m%threshold, warns=m%warns)
                end associate
            end do
        end if
        n_warnings = 0
        if (allocated(c%warnings)) n_warnings = size(c%warnings)
        call r%add('warnings', real(n_warnings, dp), '-', is_integer=.true.)
        call r%trim()
        end associate
    end subroutine case_results

    !> The array of field k of `field_names` (heights, pressure, displacement, gap); a view of the
    !> case's own array (for as long as `c` is)
    function case_field(c, k) result(x)
        type(case_t), intent(in), target :: c
        integer, intent(in) :: k
        real(dp), pointer, contiguous :: x(:, :)
        select case (k)
        case (1)
            x => c%h
        case (2)
            x => c%state%p
        case (3)
            x => c%state%u
        case default
            x => c%state%g
        end select
    end function case_field

end module veslide_quantities
