!> One case from its specification: the objects it needs (grid, heights, kernel), the solve, and
!> the analyses after it. What a case is and what it found: veslide_case_data; its outputs:
!> veslide_quantities (the catalogue) and veslide_case_file (HDF5); the memory it needs:
!> veslide_memory; the specification from an input: veslide_case_spec.
module veslide_case
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use veslide_kinds, only: dp, radians
    use veslide_error, only: error_t, fatal_error, add_context
    use veslide_clock, only: wall_seconds
    use veslide_config, only: config_t
    use veslide_grid, only: grid_t, new_grid
    use veslide_fftw, only: fft2d_t, distribute_grid
    use veslide_collective, only: share_error
    use veslide_spectrum, only: slope_tensor
    use veslide_surface, only: psd_t, random_surface, cosine_surface, bisinusoid_surface, &
                               paraboloid_surface, cylinder_surface
    use veslide_kernel, only: kernel_t, new_kernel, KERNEL_SPECTRAL
    use veslide_persson, only: persson_estimate
    use veslide_contact, only: contact_problem_t, contact_fields_t, new_contact_problem_moving
    use veslide_solver_options, only: solver_options_t, solver_progress_callback
    use veslide_solver, only: solve_contact
    use veslide_analysis, only: slope_force
    use veslide_fields, only: field_mean, field_max
    use veslide_anisotropy, only: tensor_axes, decompose
    use veslide_patches, only: contact_patches, percolates
    use veslide_topography, only: read_topography
    use veslide_memory, only: size_and_check_memory
    use veslide_system, only: use_threads
    use veslide_case_data, only: case_spec_t, case_t
    use veslide_case_spec, only: case_spec_of
    use veslide_validity, only: case_validity, check_surface_scale
    use veslide_edges, only: edge_energies, edges_measured
    implicit none
    private
    public :: case_t, build_surface, build_kernel, case_grid, run_case, solve_prepared

    !> Build and solve one case, from its specification or from a configuration (resolved first)
    interface run_case
        module procedure run_case_spec, run_case_config
    end interface run_case

contains

    !> The grid of a specification
    subroutine case_grid(spec, grid, error)
        type(case_spec_t), intent(in) :: spec
        type(grid_t), intent(out) :: grid
        type(error_t), allocatable, intent(out) :: error
        call new_grid(grid, spec%nx, spec%ny, spec%lx_m, spec%ly_m, error)
        call add_context(error, "veslide: "//spec%input_path//": &grid: ")
    end subroutine case_grid

    !> Rigid heights of a specification; with `on` (a grid already made, perhaps distributed),
    !> the heights of its rows
    subroutine build_surface(spec, h, error, on)
        type(case_spec_t), intent(in) :: spec
        real(dp), allocatable, intent(out) :: h(:, :)
        type(error_t), allocatable, intent(out) :: error
        type(grid_t), intent(in), optional :: on
        type(grid_t) :: grid
        type(psd_t) :: psd
        real(dp) :: q0
        associate (s => spec%surface)
            if (s%kind == 'file') then       ! its grid is the specification's (the input's reading)
                if (present(on)) then
                    call read_topography(s%file, s%dataset, h, error, rows=[on%j0, on%ny_local])
                else
                    call read_topography(s%file, s%dataset, h, error)
                end if
                call add_context(error, "veslide: "//spec%input_path//": &surface ")
                if (allocated(error)) return
                if (size(h, 1) /= spec%nx .or. (.not. present(on) .and. size(h, 2) /= spec%ny)) &
                    call fatal_error(error, "veslide: "//spec%input_path//": &surface file '"//s%file// &
                                     "' changed while the run read it")
                return
            end if
            if (present(on)) then
                grid = on
            else
                call case_grid(spec, grid, error); if (allocated(error)) return
            end if
            allocate (h(grid%nx, grid%ny_local))
            select case (s%kind)
            case ('self_affine')
                q0 = grid%q0()
                psd = psd_t(hurst=s%hurst, eccentricity=s%eccentricity, alpha_rad=s%alpha_rad, &
                            q_low=s%k_low*q0, q_roll=s%k_roll*q0, q_cut=s%k_cut*q0)
                call random_surface(grid, psd, s%seed, s%rms_slope, s%rms_height_m, h, error, realised=s%realised)
                call add_context(error, "veslide: "//spec%input_path//": &surface: ")
            case ('cosine')
                call cosine_surface(grid, s%amplitude_m, s%wavelength_m, s%direction_rad, h)
            case ('bisinusoid')
                call bisinusoid_surface(grid, s%amplitude_m, s%wavelength_m, h)
            case ('paraboloid')
                call paraboloid_surface(grid, s%radius_m, h)
            case ('cylinder')
                call cylinder_surface(grid, s%radius_m, h)
            case ('flat')
                h = 0.0_dp
            end select
        end associate
    end subroutine build_surface

    !> The kernel of a specification on `grid` (its solid, velocity, variant and interfacial shear)
    subroutine build_kernel(spec, grid, kernel, seconds, error)
        type(case_spec_t), intent(in) :: spec
        type(grid_t), intent(in) :: grid
        type(kernel_t), intent(out) :: kernel
        real(dp), intent(out) :: seconds
        type(error_t), allocatable, intent(out) :: error
        real(dp) :: t0
        t0 = wall_seconds()
        call new_kernel(kernel, grid, spec%material%solid, spec%velocity(), spec%kernel_variant, error, &
                        alias_tol=spec%alias_tol, alias_max=spec%alias_max, shear=spec%shear())
        call add_context(error, "veslide: "//spec%input_path//": &solver kernel = '"//spec%kernel_name()//"': ")
        seconds = wall_seconds() - t0
    end subroutine build_kernel

    !> run_case for a configuration: its specification, then the case
    subroutine run_case_config(cfg, c, error, comm, node_ranks, progress)
        type(config_t), intent(in) :: cfg
        type(case_t), intent(out) :: c
        type(error_t), allocatable, intent(out) :: error
        integer, intent(in), optional :: comm, node_ranks
        procedure(solver_progress_callback), optional :: progress
        type(case_spec_t) :: spec
        call case_spec_of(cfg, spec, error); if (allocated(error)) return
        call run_case_spec(spec, c, error, comm, node_ranks, progress)
    end subroutine run_case_config

    !> Build and solve one case; with `comm` (an MPI communicator, the MPI build) on a grid shared
    !> by its processes, `node_ranks` of them on this machine (collective: every process returns
    !> the same verdict); `progress` is told about the solve every few seconds
    subroutine run_case_spec(spec, c, error, comm, node_ranks, progress)
        type(case_spec_t), intent(in) :: spec
        type(case_t), intent(out) :: c
        type(error_t), allocatable, intent(out) :: error
        integer, intent(in), optional :: comm, node_ranks
        procedure(solver_progress_callback), optional :: progress
        type(fft2d_t) :: fft
        real(dp) :: t0
        integer :: ranks
        c%spec = spec
        ranks = 1
        if (present(comm)) then
            call new_grid(c%grid, 1, 1, 1.0_dp, 1.0_dp, error)      ! the number of processes first
            if (.not. allocated(error)) call distribute_grid(c%grid, comm, error)
            if (allocated(error)) return
            ranks = c%grid%ranks
        end if
        call size_and_check_memory(spec, c%memory_estimate_bytes, error, ranks, node_ranks, c%device_estimate_bytes)
        call share_error(c%grid, error); if (allocated(error)) return
        call case_grid(spec, c%grid, error); if (allocated(error)) return
        if (present(comm)) then
            call distribute_grid(c%grid, comm, error); if (allocated(error)) return
        end if
        t0 = wall_seconds()
        call build_surface(spec, c%h, error, on=c%grid)
        call share_error(c%grid, error); if (allocated(error)) return
        c%surface_seconds = wall_seconds() - t0
        call use_threads(spec%threads)
        call fft%init(c%grid%nx, c%grid%ny, error, planner=spec%fft_planner, grid=c%grid)
        if (allocated(error)) return
        call check_surface_scale(spec, c%grid, fft, c%h, error, c%surface_rms_slope)      ! (collective)
        if (allocated(error)) return
        call build_kernel(spec, c%grid, c%kernel, c%kernel_seconds, error); if (allocated(error)) return
        call solve_prepared(fft, c, error, progress=progress)
        call share_error(c%grid, error)
        call fft%destroy()
    end subroutine run_case_spec

    !> Solve a case whose specification, heights and kernel are set, then run its analyses;
    !> `p_init`, `g_init` warm-start the solver (a speed sweep passes the previous speed's solution);
    !> `progress` is told about the solve every few seconds
    subroutine solve_prepared(fft, c, error, p_init, g_init, progress, keep, same_heights)
        type(fft2d_t), intent(inout) :: fft
        type(case_t), intent(inout) :: c
        type(error_t), allocatable, intent(out) :: error
        real(dp), intent(in), optional :: p_init(:, :), g_init(:, :)
        procedure(solver_progress_callback), optional :: progress
        !> a study's device fields, kept from case to case of a chain (solve_contact's)
        type(contact_fields_t), intent(inout), optional :: keep
        logical, intent(in), optional :: same_heights
        type(contact_problem_t) :: problem
        type(solver_options_t) :: opts
        real(dp) :: t0, d_given
        c%grid = c%kernel%grid
        ! approach control: the mean gap of the approach since first contact (D = h_max - approach,
        ! d = D - h_mean; quantities' approach_m)
        if (c%spec%approach_m /= huge(1.0_dp)) d_given = field_max(c%grid, c%h) - field_mean(c%grid, c%h) - &
                                                          c%spec%approach_m
        ! the problem holds the case's kernel and heights while it lives (no copies)
        call new_contact_problem_moving(problem, c%kernel, c%h, c%spec%mean_pressure_pa, error, law=c%spec%law)
        call add_context(error, "veslide: "//c%spec%input_path//": ")
        if (allocated(error)) return
        if (c%spec%approach_m /= huge(1.0_dp)) then
            problem%approach_control = .true.
            problem%mean_gap_m = d_given
        end if
        t0 = wall_seconds()
        opts = c%spec%solver
        if (present(progress)) opts%progress => progress
        call solve_contact(problem, fft, opts, c%state, error, p_init=p_init, g_init=g_init, keep=keep, &
                           same_heights=same_heights)
        call problem%release(c%kernel, c%h)
        if (allocated(error)) return
        c%solve_seconds = wall_seconds() - t0
        ! under approach control the load is the solve's
        if (c%spec%approach_m /= huge(1.0_dp)) c%spec%mean_pressure_pa = field_mean(c%grid, c%state%p)
        c%force_pa = c%kernel%tangential_force(fft, c%state%p)
        c%interfacial_force_pa = 0.0_dp
        if (c%spec%shear_coefficient > 0.0_dp) &
            c%interfacial_force_pa = c%spec%shear_coefficient*field_mean(c%grid, c%state%p)
        call slope_force(c%grid, fft, c%state%p, c%h, c%slope_force_pa)
        call case_validity(c, fft)
        if (c%spec%law%adhesive()) then
            call edge_analysis(fft, c, error); if (allocated(error)) return
        end if
        c%have_anisotropy = .false.; c%have_patches = .false.; c%have_persson = .false.
        if (c%spec%analysis%anisotropy) call anisotropy_analysis(fft, c)
        if (c%spec%analysis%persson .and. .not. c%spec%law%adhesive()) then
            if (c%grid%is_distributed()) then
                call fatal_error(error, "veslide: "//c%spec%input_path//": &analysis persson = .true. is not available on a"// &
                    " grid distributed over processes (the theory orders every mode of the spectrum by |q|):"// &
                    " set persson = .false., or run the case on one process")
                return
            end if
            call persson_analysis(fft, c, error); if (allocated(error)) return
        end if
        if (c%spec%analysis%patches) then
            ! the contact cells are the law's
            call contact_patches(c%spec%law%contact(c%state%p, c%state%g), c%grid%lx_m, c%grid%ly_m, c%patches, c%grid)
            c%percolates_x = percolates(.not. c%spec%law%contact(c%state%p, c%state%g), 1, c%grid)
            c%percolates_y = percolates(.not. c%spec%law%contact(c%state%p, c%state%g), 2, c%grid)
            c%have_patches = .true.
        end if
    end subroutine solve_prepared

    !> The energy release rates of an adhesive contact's trailing and leading edges (veslide_edges),
    !> with the relaxed solid's misfit u0 - u from the kernel at rest: zero for an elastic solid or at rest.
    !> Only for a line contact along the motion (NaN otherwise, with nothing formed: no memory)
    subroutine edge_analysis(fft, c, error)
        type(fft2d_t), intent(inout) :: fft
        type(case_t), intent(inout) :: c
        type(error_t), allocatable, intent(out) :: error
        type(kernel_t) :: relaxed
        real(dp), allocatable :: delta(:, :)
        real(dp) :: zone
        c%trailing_edge_energy = ieee_value(1.0_dp, ieee_quiet_nan); c%trailing_edges = 0
        c%leading_edge_energy = c%trailing_edge_energy; c%leading_edges = 0
        ! (a line contact along the motion only: nothing is formed otherwise)
        if (.not. edges_measured(c%grid, radians(c%spec%direction_deg))) return
        allocate (delta(size(c%state%u, 1), size(c%state%u, 2)))
        delta = 0.0_dp
        if (c%spec%speed_m_s > 0.0_dp .and. .not. c%spec%material%solid%is_elastic()) then
            call new_kernel(relaxed, c%grid, c%spec%material%solid, [0.0_dp, 0.0_dp], c%spec%kernel_variant, error, &
                            alias_tol=c%spec%alias_tol, alias_max=c%spec%alias_max, shear=c%spec%shear())
            call add_context(error, "veslide: "//c%spec%input_path//": the relaxed kernel of the edges' measure: ")
            if (allocated(error)) return
            call relaxed%apply(fft, c%state%p, delta)
            delta = delta - c%state%u
        end if
        associate (solid => c%spec%material%solid)
            zone = c%spec%law%zone(solid%e0_pa/(1.0_dp - solid%poisson**2))
        end associate
        call edge_energies(c%spec%law, c%state%g, c%state%p, delta, c%grid, radians(c%spec%direction_deg), zone, &
                           c%trailing_edge_energy, c%trailing_edges, c%leading_edge_energy, c%leading_edges)
    end subroutine edge_analysis

    !> Persson's theory on the realised spectrum of the heights, with the case's solid, velocity and
    !> load (the spectral kernel: the case's own when it is spectral)
    subroutine persson_analysis(fft, c, error)
        type(fft2d_t), intent(inout) :: fft
        type(case_t), intent(inout) :: c
        type(error_t), allocatable, intent(out) :: error
        type(kernel_t) :: spectral
        fft%x = c%h
        call fft%forward()
        if (c%kernel%variant == KERNEL_SPECTRAL) then
            call persson_estimate(c%kernel, fft%k/c%grid%cells(), c%spec%mean_pressure_pa, c%persson, error, &
                                  s_correction=c%spec%analysis%persson_correction)
        else
            call new_kernel(spectral, c%grid, c%spec%material%solid, c%spec%velocity(), KERNEL_SPECTRAL, error, &
                            shear=c%spec%shear())
            if (allocated(error)) return
            call persson_estimate(spectral, fft%k/c%grid%cells(), c%spec%mean_pressure_pa, c%persson, error, &
                                  s_correction=c%spec%analysis%persson_correction)
        end if
        call add_context(error, "veslide: "//c%spec%input_path//": &analysis persson: ")
        c%have_persson = .not. allocated(error)
    end subroutine persson_analysis

    !> Slope tensors of h and of the deformed surface w in the band [zeta1, zeta2] q0, and eq. (16)
    subroutine anisotropy_analysis(fft, c)
        type(fft2d_t), intent(inout) :: fft
        type(case_t), intent(inout) :: c
        real(dp) :: l1, l2
        c%band_q = [c%spec%analysis%zeta1, c%spec%analysis%zeta2]*c%grid%q0()
        call slope_tensor(c%grid, fft, c%h, c%m_surface, band=c%band_q)
        call slope_tensor(c%grid, fft, c%state%u, c%m_deformed, band=c%band_q)
        call tensor_axes(c%m_surface, l1, l2, c%theta_s); c%gamma_s = l2/l1
        call tensor_axes(c%m_deformed, l1, l2, c%theta_d); c%gamma_d = l2/l1
        call decompose(c%m_surface, c%m_deformed, c%spec%analysis%iso_tol, c%sigma1, c%sigma2, c%phi)
        c%have_anisotropy = .true.
    end subroutine anisotropy_analysis

end module veslide_case
