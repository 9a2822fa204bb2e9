!> What a case is asked (`case_spec_t`) and what it found (`case_t`): plain data, no procedures
!> that compute.
!>
!> A specification is resolved once from the input (veslide_case_spec, in io) and never edited
!> while it is used: SI units and radians, the solid as a `material_t` (its times already shifted
!> to the case's temperature), the sliding velocity as speed and direction (`velocity`, the one
!> source the kernel, Persson's theory and the output read), the load, the solver's options, the
!> kernel variant, the interfacial shear, the analyses and whether fields are written. A study makes one specification
!> per case from its input (veslide_study); nothing writes the configuration after it is read.
!>
!> It sits in the analysis layer because the output catalogue (veslide_quantities) reads both
!> types and the case writer (veslide_case_file, io) writes them; the driver builds the objects
!> of a case from a specification (veslide_case).
module veslide_case_data
    use veslide_kinds, only: dp, i8, radians
    use veslide_grid, only: grid_t
    use veslide_material, only: material_t
    use veslide_kernel, only: kernel_t, KERNEL_SPECTRAL, kernel_names
    use veslide_contact, only: contact_state_t
    use veslide_contact_law, only: contact_law_t
    use veslide_solver_options, only: solver_options_t
    use veslide_patches, only: patch_stats_t
    use veslide_persson, only: persson_t
    use veslide_warning, only: warning_t, measure_t
    implicit none
    private
    public :: case_spec_t, surface_spec_t, material_spec_t, analysis_spec_t, case_t

    !> The rigid surface: a kind and what that kind reads (lengths in m, angles in radians; the
    !> cut-offs k_* in units of q0 = 2 pi/lx_m)
    type :: surface_spec_t
        character(len=:), allocatable :: kind            !! &surface kind
        integer(i8) :: seed = 1_i8
        real(dp) :: hurst = 0.8_dp, eccentricity = 1.0_dp, alpha_rad = 0.0_dp
        real(dp) :: k_low = 1.0_dp, k_roll = 1.0_dp, k_cut = 64.0_dp
        real(dp) :: rms_slope = 0.0_dp, rms_height_m = 0.0_dp
        logical :: realised = .true.                     !! scale the realised surface, not its expectation
        real(dp) :: amplitude_m = 0.0_dp, wavelength_m = 0.0_dp, direction_rad = 0.0_dp, radius_m = 0.0_dp
        character(len=:), allocatable :: file, dataset   !! kind = 'file': the height file and dataset
        character(len=:), allocatable :: preparation     !! the file's record of its preparation ('')
        !> kind = 'file': its edge jumps along x and y and the rms steps inside [h_rms]; the share
        !> of the scan filled and of its slope variance the band removed (-1: not stated)
        real(dp) :: edge_jump(2) = 0.0_dp, edge_step(2) = 0.0_dp
        real(dp) :: filled_fraction = -1.0_dp, band_slope_removed = -1.0_dp
    end type surface_spec_t

    !> The solid: the model's name (for the reader), the resolved `material_t`, and the temperature
    !> it was resolved at with the shift factor applied to its times
    type :: material_spec_t
        character(len=:), allocatable :: model           !! &material model
        type(material_t) :: solid
        logical :: shifted = .false.                     !! a time-temperature shift applies
        real(dp) :: temperature_c = 0.0_dp, shift_factor = 1.0_dp
    end type material_spec_t

    !> The analyses after the solve (&analysis; zeta in units of q0)
    type :: analysis_spec_t
        logical :: anisotropy = .false.
        real(dp) :: zeta1 = 1.0_dp, zeta2 = 64.0_dp
        integer :: n_theta = 72
        real(dp) :: iso_tol = 1.0e-3_dp
        logical :: patches = .false., persson = .false., persson_correction = .false.
    end type analysis_spec_t

    !> One case, resolved
    type :: case_spec_t
        character(len=:), allocatable :: input_path      !! the input it came from (messages, provenance)
        character(len=:), allocatable :: input_text      !! its text, verbatim (provenance)
        integer :: nx = 0, ny = 0
        real(dp) :: lx_m = 0.0_dp, ly_m = 0.0_dp
        type(surface_spec_t) :: surface
        type(material_spec_t) :: material
        real(dp) :: speed_m_s = 0.0_dp                   !! of the rigid surface [m/s]
        real(dp) :: direction_deg = 0.0_dp               !! of the velocity from x [degree]
        real(dp) :: mean_pressure_pa = 0.0_dp            !! the nominal pressure [Pa]
        !> approach control (an adhesive law's): the rigid-body approach since first contact [m];
        !> huge() under load control. After the solve mean_pressure_pa is the load it found.
        real(dp) :: approach_m = huge(1.0_dp)
        !> mu_f of a full-slip Coulomb shear at the interface (&interface; 0: none) [-]
        real(dp) :: shear_coefficient = 0.0_dp
        type(contact_law_t) :: law                       !! the contact law (the hard wall)
        type(solver_options_t) :: solver
        integer :: kernel_variant = KERNEL_SPECTRAL      !! KERNEL_* id
        real(dp) :: alias_tol = 1.0e-6_dp
        integer :: alias_max = 64
        character(len=:), allocatable :: fft_planner
        integer :: threads = 0                           !! OpenMP threads (0: OMP_NUM_THREADS)
        type(analysis_spec_t) :: analysis
        logical :: fields = .true.                       !! write the 2-D fields
        !> what the input's reading found questionable (source 'input'), kept with every case
        type(warning_t), allocatable :: warnings(:)
    contains
        procedure :: velocity => spec_velocity
        procedure :: shear => spec_shear
        procedure :: kernel_name => spec_kernel_name
    end type case_spec_t

    !> A case: its specification, the objects built from it, and everything one solve produced
    type :: case_t
        type(case_spec_t) :: spec
        type(grid_t) :: grid
        real(dp), allocatable :: h(:, :)          !! rigid heights [m]
        real(dp) :: surface_rms_slope = -1.0_dp   !! of h, measured once per surface (-1: not yet)
        type(kernel_t) :: kernel
        type(contact_state_t) :: state
        real(dp) :: force_pa(2) = 0.0_dp          !! <p grad w>, solid on rigid surface [Pa]
        real(dp) :: slope_force_pa(2) = 0.0_dp    !! <p grad h> [Pa] (check)
        !> mu_f <p>: the interfacial shear's force on the rigid surface per nominal area, along -v_hat [Pa]
        real(dp) :: interfacial_force_pa = 0.0_dp
        !> an adhesive law's: the mean energy release rates of the contact's trailing and leading
        !> edges [J/m^2] (NaN where none is measured) and their numbers (veslide_edges)
        real(dp) :: trailing_edge_energy = 0.0_dp, leading_edge_energy = 0.0_dp
        integer :: trailing_edges = 0, leading_edges = 0
        real(dp) :: kernel_seconds = 0.0_dp, solve_seconds = 0.0_dp, surface_seconds = 0.0_dp
        integer(i8) :: memory_estimate_bytes = 0    !! estimated peak of the run, before allocating [bytes]
        integer(i8) :: device_estimate_bytes = 0    !! estimated peak on the device (0: solved on the CPU) [bytes]
        ! &analysis anisotropy
        logical :: have_anisotropy = .false.
        real(dp) :: band_q(2) = 0.0_dp                    !! [zeta1, zeta2] q0 [1/m]
        real(dp) :: m_surface(2, 2) = 0.0_dp, m_deformed(2, 2) = 0.0_dp
        real(dp) :: gamma_s = 0.0_dp, gamma_d = 0.0_dp, theta_s = 0.0_dp, theta_d = 0.0_dp
        real(dp) :: sigma1 = 0.0_dp, sigma2 = 0.0_dp, phi = 0.0_dp
        ! &analysis patches
        logical :: have_patches = .false.
        type(patch_stats_t) :: patches
        logical :: percolates_x = .false., percolates_y = .false.
        ! &analysis persson
        logical :: have_persson = .false.
        type(persson_t) :: persson
        ! its validity (veslide_validity): the measures, and the warnings of its input and result
        type(measure_t), allocatable :: validity(:)
        type(warning_t), allocatable :: warnings(:)
    end type case_t

contains

    !> The velocity of the rigid surface [m/s]: speed along direction
    pure function spec_velocity(self) result(v)
        class(case_spec_t), intent(in) :: self
        real(dp) :: v(2), th
        th = radians(self%direction_deg)
        v = self%speed_m_s*[cos(th), sin(th)]
    end function spec_velocity

    !> The interfacial shear traction on the solid per unit contact pressure, mu_f v_hat [-]: along
    !> the direction of the velocity, whatever the speed (v = 0 is the limit of slow sliding, where
    !> a Coulomb friction keeps its value)
    pure function spec_shear(self) result(s)
        class(case_spec_t), intent(in) :: self
        real(dp) :: s(2), th
        th = radians(self%direction_deg)
        s = self%shear_coefficient*[cos(th), sin(th)]
    end function spec_shear

    !> The kernel variant's name (&solver kernel)
    pure function spec_kernel_name(self) result(name)
        class(case_spec_t), intent(in) :: self
        character(len=:), allocatable :: name
        name = trim(kernel_names(self%kernel_variant))
    end function spec_kernel_name

end module veslide_case_data
