!> One case from a configuration: surface, material, kernel, contact problem, solve, derived
!> quantities, and its results (the list the output, the study rows and the summary read).
module veslide_case
    use veslide_kinds, only: dp, i8, pi, radians
    use veslide_error, only: error_t, fatal_error, add_context
    use veslide_clock, only: wall_seconds
    use veslide_strings, only: str
    use veslide_version, only: version_string
    use veslide_config, only: config_t
    use veslide_grid, only: grid_t, new_grid
    use veslide_fftw, only: fft2d_t, distribute_grid
    use veslide_collective, only: share_error, global_max
    use veslide_fields, only: field_rms, field_max, field_mean
    use veslide_spectrum, only: slope_tensor
    use veslide_material, only: material_t, new_elastic, new_one_term, new_creep, new_relaxation, shift_factor, &
                                BASE_BONDED, BASE_FRICTIONLESS
    use veslide_surface, only: psd_t, random_surface, cosine_surface, bisinusoid_surface, &
                               paraboloid_surface, cylinder_surface, rms_height
    use veslide_kernel, only: kernel_t, new_kernel, kernel_variant_id, KERNEL_SPECTRAL
    use veslide_persson, only: persson_t, persson_estimate
    use veslide_contact, only: contact_problem_t, contact_state_t, new_contact_problem_moving
    use veslide_solver_options, only: solver_options_t, solver_method_id, solver_progress_callback, device_choice_id
    use veslide_solver, only: solve_contact
    use veslide_analysis, only: contact_area_fraction, contact_area_subcell, mean_separation, slope_force
    use veslide_anisotropy, only: tensor_axes, decompose, m2_of_theta
    use veslide_patches, only: patch_stats_t, contact_patches, percolates
    use veslide_quantities, only: results_t, add_force_quantities, add_solver_quantities
    use veslide_topography, only: read_topography
    use veslide_memory, only: memory_estimate_bytes, device_estimate_bytes, format_gib
    use veslide_device, only: device_info_t, device_info, device_memory
    use veslide_solver, only: auto_takes_device, check_device_choice
    use veslide_system, only: available_memory_bytes, peak_memory_bytes, use_threads
    use veslide_hdf5, only: h5file_t
    use veslide_hdf5_parallel, only: create_collective, write_rows
    use veslide_output, only: write_provenance, write_results, write_field, field_layout
    implicit none
    private
    public :: case_t, build_surface, build_material, build_kernel, case_grid, run_case, solve_prepared, &
              case_results, write_case, write_case_group, velocity_of, size_and_check_memory, summary_lines, summary_width, &
              case_memory, case_on_device

    !> The length of a line of the run summary: two texts of the input (up to 1023 characters
    !> each, the input's and the output's paths) and the words around them, never cut
    integer, parameter :: summary_width = 2200

    !> Everything one solve produced
    type :: case_t
        type(grid_t) :: grid
        real(dp), allocatable :: h(:, :)          !! rigid heights [m]
        type(material_t) :: mat
        type(kernel_t) :: kernel
        type(contact_state_t) :: state
        real(dp) :: velocity_m_s(2) = 0.0_dp
        real(dp) :: force_pa(2) = 0.0_dp          !! <p grad w>, solid on rigid surface [Pa]
        real(dp) :: slope_force_pa(2) = 0.0_dp    !! <p grad h> [Pa] (check)
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
    end type case_t

contains

    !> The velocity vector of &motion [m/s]
    pure function velocity_of(cfg) result(v)
        type(config_t), intent(in) :: cfg
        real(dp) :: v(2), th
        th = radians(cfg%motion%direction_deg)
        v = cfg%motion%speed_m_s*[cos(th), sin(th)]
    end function velocity_of

    !> The grid of the configuration (for a measured topography, after build_surface read it)
    subroutine case_grid(cfg, grid, error)
        type(config_t), intent(in) :: cfg
        type(grid_t), intent(out) :: grid
        type(error_t), allocatable, intent(out) :: error
        call new_grid(grid, cfg%grid%nx, cfg%grid%ny, cfg%grid%lx_m, cfg%grid%ly_m, error)
        call add_context(error, "veslide: "//cfg%path//": &grid: ")
    end subroutine case_grid

    !> Rigid heights from the configuration; a measured topography fixes &grid nx, ny, lx_m, ly_m.
    !> With `on` (a grid already made, perhaps distributed), the heights of its rows.
    subroutine build_surface(cfg, h, error, on)
        type(config_t), intent(inout) :: cfg
        real(dp), allocatable, intent(out) :: h(:, :)
        type(error_t), allocatable, intent(out) :: error
        type(grid_t), intent(in), optional :: on
        type(grid_t) :: grid
        type(psd_t) :: psd
        real(dp) :: q0
        if (cfg%surface%kind == 'file') then       ! its grid is cfg%grid (complete_config)
            if (present(on)) then
                call read_topography(cfg%surface%file, cfg%surface%dataset, h, error, rows=[on%j0, on%ny_local])
            else
                call read_topography(cfg%surface%file, cfg%surface%dataset, h, error)
            end if
            call add_context(error, "veslide: "//cfg%path//": &surface ")
            if (allocated(error)) return
            if (size(h, 1) /= cfg%grid%nx .or. (.not. present(on) .and. size(h, 2) /= cfg%grid%ny)) &
                call fatal_error(error, "veslide: "//cfg%path//": &surface file '"//cfg%surface%file// &
                                 "' changed while the run read it")
            return
        end if
        if (present(on)) then
            grid = on
        else
            call case_grid(cfg, grid, error); if (allocated(error)) return
        end if
        allocate (h(grid%nx, grid%ny_local))
        associate (s => cfg%surface)
            select case (s%kind)
            case ('self_affine')
                q0 = grid%q0()
                psd = psd_t(hurst=s%hurst, eccentricity=s%eccentricity, alpha_rad=radians(s%alpha_deg), &
                            q_low=s%k_low*q0, q_roll=s%k_roll*q0, q_cut=s%k_cut*q0)
                call random_surface(grid, psd, s%seed, s%rms_slope, s%rms_height_m, h, error, &
                                    realised=s%scale_to == 'realised')
                call add_context(error, "veslide: "//cfg%path//": &surface: ")
            case ('cosine')
                call cosine_surface(grid, s%amplitude_m, s%wavelength_m, radians(s%direction_deg), h)
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

    !> The solid from &material
    subroutine build_material(cfg, mat, error)
        type(config_t), intent(in) :: cfg
        type(material_t), intent(out) :: mat
        type(error_t), allocatable, intent(out) :: error
        real(dp) :: a
        associate (m => cfg%material)
            a = material_shift(cfg)     ! the master curve's times at the test temperature
            select case (m%model)
            case ('elastic')
                call new_elastic(mat, m%young_pa, m%poisson, error)
            case ('one_term')
                call new_one_term(mat, m%einf_pa, m%ratio, a*m%tau_s, m%poisson, error)
            case ('creep')
                call new_creep(mat, m%e0_pa, m%prony_coef, a*m%prony_time_s, m%poisson, error)
            case ('relaxation')
                call new_relaxation(mat, m%e0_pa, m%prony_coef, a*m%prony_time_s, m%poisson, error)
            end select
            if (.not. allocated(error) .and. m%thickness_m > 0.0_dp) then
                mat%thickness_m = m%thickness_m
                mat%base = merge(BASE_BONDED, BASE_FRICTIONLESS, m%base == 'bonded')
            end if
        end associate
        call add_context(error, "veslide: "//cfg%path//": &material: ")
    end subroutine build_material

    !> The shift factor a_T of the configuration's material at its temperature (1 without a shift)
    pure real(dp) function material_shift(cfg) result(a)
        type(config_t), intent(in) :: cfg
        associate (m => cfg%material)
            a = shift_factor(m%shift, m%temperature_c, m%reference_temperature_c, m%wlf_c1, m%wlf_c2_k, &
                             m%activation_energy_j_mol)
        end associate
    end function material_shift

    !> The kernel of a grid, material and the configuration's velocity
    subroutine build_kernel(cfg, grid, mat, kernel, seconds, error)
        type(config_t), intent(in) :: cfg
        type(grid_t), intent(in) :: grid
        type(material_t), intent(in) :: mat
        type(kernel_t), intent(out) :: kernel
        real(dp), intent(out) :: seconds
        type(error_t), allocatable, intent(out) :: error
        real(dp) :: t0
        t0 = wall_seconds()
        call new_kernel(kernel, grid, mat, velocity_of(cfg), kernel_variant_id(cfg%solver%kernel), error, &
                        alias_tol=cfg%solver%alias_tol, alias_max=cfg%solver%alias_max)
        call add_context(error, "veslide: "//cfg%path//": &solver kernel = '"//cfg%solver%kernel//"': ")
        seconds = wall_seconds() - t0
    end subroutine build_kernel

    !> Before anything is allocated: the grid of a measured topography (from the file's shape and
    !> its length_m attribute), and the memory the run will need against what the process may use;
    !> refused in one line naming &grid nx, ny (or the file) when it does not fit. Returns the
    !> estimate. On a grid shared by `ranks` processes, `node_ranks` of them on this machine, the
    !> estimate is one process's share and the memory free on the machine is shared among those.
    !> A case solved on the device is refused, in the same way, when the device's estimate
    !> (`device_estimate`, 0 for a case on the CPU) exceeds the device's free memory.
    subroutine size_and_check_memory(cfg, estimate, error, ranks, node_ranks, device_estimate)
        type(config_t), intent(inout) :: cfg
        integer(i8), intent(out) :: estimate
        type(error_t), allocatable, intent(out) :: error
        integer, intent(in), optional :: ranks, node_ranks
        integer(i8), intent(out), optional :: device_estimate
        integer(i8) :: available, dev
        integer :: ranks_, node_ranks_
        character(len=:), allocatable :: what, who
        ranks_ = 1; if (present(ranks)) ranks_ = max(1, ranks)
        node_ranks_ = 1; if (present(node_ranks)) node_ranks_ = max(1, node_ranks)
        if (present(device_estimate)) device_estimate = 0
        call check_device_choice(device_choice_id(cfg%solver%device), error)
        call add_context(error, "veslide: "//cfg%path//": ")
        if (allocated(error)) return
        what = "&grid nx, ny = "
        if (cfg%surface%kind == 'file') what = "&surface file '"//cfg%surface%file//"' of "
        call case_memory(cfg, estimate, error, ranks_, dev); if (allocated(error)) return
        if (present(device_estimate)) device_estimate = dev
        if (dev > 0) then
            call check_device_memory(cfg, dev, error); if (allocated(error)) return
        end if
        available = available_memory_bytes()
        if (available >= 0) available = available/node_ranks_
        if (available >= 0 .and. estimate > available) then
            what = what//str(cfg%grid%nx)//" x "//str(cfg%grid%ny)
            who = "this process (free memory, ulimit and cgroup limits)"
            if (ranks_ > 1) then
                what = what//" on "//str(ranks_)//" processes"
                who = "each of the "//str(node_ranks_)//" processes on this machine (its share of the free memory,"// &
                      " ulimit and cgroup limits)"
            end if
            call fatal_error(error, "veslide: "//cfg%path//": "//what//" needs about "//format_gib(estimate)// &
                " of memory per process, and "//format_gib(available)//" is available to "//who// &
                ": choose a smaller &grid nx, ny, use more processes, or run where more memory is free")
        end if
    end subroutine size_and_check_memory

    !> The device estimate `dev` against the device's free memory (refused in one line naming both)
    subroutine check_device_memory(cfg, dev, error)
        type(config_t), intent(in) :: cfg
        integer(i8), intent(in) :: dev
        type(error_t), allocatable, intent(out) :: error
        type(device_info_t) :: info
        real(dp) :: free_b, total_b
        call device_memory(free_b, total_b, error); if (allocated(error)) return
        if (free_b < 0.0_dp .or. real(dev, dp) <= free_b) return
        call device_info(info, error); if (allocated(error)) return
        call fatal_error(error, "veslide: "//cfg%path//": &grid nx, ny = "//str(cfg%grid%nx)//" x "// &
            str(cfg%grid%ny)//" needs about "//format_gib(dev)//" of device memory, and "// &
            format_gib(int(free_b, i8))//" is free on the "//info%name//" (of "//format_gib(int(total_b, i8))// &
            "): choose a smaller &grid nx, ny, a device with more memory, or &solver device = 'cpu'")
    end subroutine check_device_memory

    !> Will the case of `cfg` be solved on the device (on `ranks` processes: never shared)?
    logical function case_on_device(cfg, ranks) result(yes)
        type(config_t), intent(in) :: cfg
        integer, intent(in), optional :: ranks
        yes = .false.
        if (present(ranks)) then
            if (ranks > 1) return
        end if
        select case (cfg%solver%device)
        case ('gpu')
            yes = cfg%solver%method /= 'pk'          ! (what it does not run is refused at the solve)
        case ('auto')
            yes = auto_takes_device(solver_method_id(cfg%solver%method), cfg%solver%anderson_memory, .false.)
        end select
    end function case_on_device

    !> The memory the case or study of `cfg` will need, per process when `ranks` processes share its
    !> grid [bytes], before anything is allocated (a measured topography's grid is the file's); with
    !> `device_estimate`, what a solve on the device holds there (0: the case is solved on the CPU)
    subroutine case_memory(cfg, estimate, error, ranks, device_estimate)
        type(config_t), intent(inout) :: cfg
        integer(i8), intent(out) :: estimate
        type(error_t), allocatable, intent(out) :: error
        integer, intent(in), optional :: ranks
        integer(i8), intent(out), optional :: device_estimate
        logical :: device
        estimate = 0
        if (present(device_estimate)) device_estimate = 0
        device = case_on_device(cfg, ranks)
        estimate = memory_estimate_bytes(cfg, ranks, device)
        if (device .and. present(device_estimate)) device_estimate = device_estimate_bytes(cfg)
    end subroutine case_memory

    !> Build and solve one case; with `comm` (an MPI communicator, the MPI build) on a grid shared
    !> by its processes, `node_ranks` of them on this machine (collective: every process returns
    !> the same verdict); `progress` is told about the solve every few seconds
    subroutine run_case(cfg, c, error, comm, node_ranks, progress)
        type(config_t), intent(inout) :: cfg
        type(case_t), intent(out) :: c
        type(error_t), allocatable, intent(out) :: error
        integer, intent(in), optional :: comm, node_ranks
        procedure(solver_progress_callback), optional :: progress
        type(fft2d_t) :: fft
        real(dp) :: t0
        integer :: ranks
        ranks = 1
        if (present(comm)) then
            call new_grid(c%grid, 1, 1, 1.0_dp, 1.0_dp, error)      ! the number of processes first
            if (.not. allocated(error)) call distribute_grid(c%grid, comm, error)
            if (allocated(error)) return
            ranks = c%grid%ranks
        end if
        call size_and_check_memory(cfg, c%memory_estimate_bytes, error, ranks, node_ranks, c%device_estimate_bytes)
        call share_error(c%grid, error); if (allocated(error)) return
        call case_grid(cfg, c%grid, error); if (allocated(error)) return
        if (present(comm)) then
            call distribute_grid(c%grid, comm, error); if (allocated(error)) return
        end if
        t0 = wall_seconds()
        call build_surface(cfg, c%h, error, on=c%grid)
        call share_error(c%grid, error); if (allocated(error)) return
        c%surface_seconds = wall_seconds() - t0
        call use_threads(cfg%solver%threads)
        call fft%init(c%grid%nx, c%grid%ny, error, planner=cfg%solver%fft_planner, grid=c%grid)
        if (allocated(error)) return
        call build_material(cfg, c%mat, error); if (allocated(error)) return
        call build_kernel(cfg, c%grid, c%mat, c%kernel, c%kernel_seconds, error); if (allocated(error)) return
        call solve_prepared(cfg, fft, c, error, progress=progress)
        call share_error(c%grid, error)
        call fft%destroy()
    end subroutine run_case

    !> The solver options of &solver
    pure function solver_options(cfg) result(opts)
        type(config_t), intent(in) :: cfg
        type(solver_options_t) :: opts
        opts%method = solver_method_id(cfg%solver%method)
        opts%device = device_choice_id(cfg%solver%device)
        opts%tolerance = cfg%solver%tolerance
        opts%max_iterations = cfg%solver%max_iterations
        opts%anderson_memory = cfg%solver%anderson_memory
        opts%balance_every = cfg%solver%balance_every
        opts%balance_ratio = cfg%solver%balance_ratio
        opts%balance_factor = cfg%solver%balance_factor
    end function solver_options

    !> Solve a case whose heights, material and kernel are set, then derive its quantities;
    !> `p_init`, `g_init` warm-start the solver (a speed sweep passes the previous speed's solution);
    !> `progress` is told about the solve every few seconds
    subroutine solve_prepared(cfg, fft, c, error, p_init, g_init, progress)
        type(config_t), intent(in) :: cfg
        type(fft2d_t), intent(inout) :: fft
        type(case_t), intent(inout) :: c
        type(error_t), allocatable, intent(out) :: error
        real(dp), intent(in), optional :: p_init(:, :), g_init(:, :)
        procedure(solver_progress_callback), optional :: progress
        type(contact_problem_t) :: problem
        type(solver_options_t) :: opts
        real(dp) :: t0
        c%grid = c%kernel%grid
        c%velocity_m_s = c%kernel%velocity_m_s
        ! the problem holds the case's kernel and heights while it lives (no copies)
        call new_contact_problem_moving(problem, c%kernel, c%h, cfg%load%mean_pressure_pa, error)
        call add_context(error, "veslide: "//cfg%path//": ")
        if (allocated(error)) return
        t0 = wall_seconds()
        opts = solver_options(cfg)
        if (present(progress)) opts%progress => progress
        call solve_contact(problem, fft, opts, c%state, error, p_init=p_init, g_init=g_init)
        call problem%release(c%kernel, c%h)
        if (allocated(error)) return
        c%solve_seconds = wall_seconds() - t0
        c%force_pa = c%kernel%tangential_force(fft, c%state%p)
        call slope_force(c%grid, fft, c%state%p, c%h, c%slope_force_pa)
        c%have_anisotropy = .false.; c%have_patches = .false.; c%have_persson = .false.
        if (cfg%analysis%anisotropy) call anisotropy_analysis(cfg, fft, c)
        if (cfg%analysis%persson) then
            if (c%grid%is_distributed()) then
                call fatal_error(error, "veslide: "//cfg%path//": &analysis persson = .true. is not available on a"// &
                    " grid distributed over processes (the theory orders every mode of the spectrum by |q|):"// &
                    " set persson = .false., or run the case on one process")
                return
            end if
            call persson_analysis(cfg, fft, c, error); if (allocated(error)) return
        end if
        if (cfg%analysis%patches) then
            call contact_patches(c%state%p > 0.0_dp, c%grid%lx_m, c%grid%ly_m, c%patches, c%grid)
            c%percolates_x = percolates(.not. (c%state%p > 0.0_dp), 1, c%grid)
            c%percolates_y = percolates(.not. (c%state%p > 0.0_dp), 2, c%grid)
            c%have_patches = .true.
        end if
    end subroutine solve_prepared

    !> Persson's theory on the realised spectrum of the heights, with the case's solid, velocity and
    !> load (the spectral kernel: the case's own when it is spectral)
    subroutine persson_analysis(cfg, fft, c, error)
        type(config_t), intent(in) :: cfg
        type(fft2d_t), intent(inout) :: fft
        type(case_t), intent(inout) :: c
        type(error_t), allocatable, intent(out) :: error
        type(kernel_t) :: spectral
        fft%x = c%h
        call fft%forward()
        if (c%kernel%variant == KERNEL_SPECTRAL) then
            call persson_estimate(c%kernel, fft%k/c%grid%cells(), cfg%load%mean_pressure_pa, c%persson, error, &
                                  s_correction=cfg%analysis%persson_correction)
        else
            call new_kernel(spectral, c%grid, c%mat, c%velocity_m_s, KERNEL_SPECTRAL, error)
            if (allocated(error)) return
            call persson_estimate(spectral, fft%k/c%grid%cells(), cfg%load%mean_pressure_pa, c%persson, error, &
                                  s_correction=cfg%analysis%persson_correction)
        end if
        call add_context(error, "veslide: "//cfg%path//": &analysis persson: ")
        c%have_persson = .not. allocated(error)
    end subroutine persson_analysis

    !> Slope tensors of h and of the deformed surface w in the band [zeta1, zeta2] q0, and eq. (16)
    subroutine anisotropy_analysis(cfg, fft, c)
        type(config_t), intent(in) :: cfg
        type(fft2d_t), intent(inout) :: fft
        type(case_t), intent(inout) :: c
        real(dp) :: l1, l2
        c%band_q = [cfg%analysis%zeta1, cfg%analysis%zeta2]*c%grid%q0()
        call slope_tensor(c%grid, fft, c%h, c%m_surface, band=c%band_q)
        call slope_tensor(c%grid, fft, c%state%u, c%m_deformed, band=c%band_q)
        call tensor_axes(c%m_surface, l1, l2, c%theta_s); c%gamma_s = l2/l1
        call tensor_axes(c%m_deformed, l1, l2, c%theta_d); c%gamma_d = l2/l1
        call decompose(c%m_surface, c%m_deformed, cfg%analysis%iso_tol, c%sigma1, c%sigma2, c%phi)
        c%have_anisotropy = .true.
    end subroutine anisotropy_analysis

    !> The results of a case, in output order: every scalar with its units, and the arrays
    subroutine case_results(cfg, c, r)
        type(config_t), intent(in) :: cfg
        type(case_t), intent(in) :: c
        type(results_t), intent(out) :: r
        real(dp) :: along, across, d, peak
        integer :: j
        call r%add('contact_area_fraction', contact_area_subcell(c%state%p, c%state%g, c%grid), '-')
        call r%add('contact_area_fraction_cells', contact_area_fraction(c%state%p, c%grid), '-')
        call r%add('mean_separation_m', mean_separation(c%state%g, c%grid), 'm')
        call r%add('rms_height_m', field_rms(c%grid, c%h), 'm')
        call r%add('max_pressure_pa', field_max(c%grid, c%state%p), 'Pa')
        call r%add('mean_pressure_pa', cfg%load%mean_pressure_pa, 'Pa')
        ! the rigid-body approach since first contact: g = w - h + D with mean w = 0 gives
        ! D = h_max at first touch and D = h_mean + d under load (d: the solver's mean gap)
        call r%add('approach_m', field_max(c%grid, c%h) - field_mean(c%grid, c%h) - c%state%approach_m, 'm')
        call add_solver_quantities(r, c%state, cfg%solver%tolerance)
        call r%add('length_x_m', c%grid%lx_m, 'm')
        call r%add('length_y_m', c%grid%ly_m, 'm')
        call r%add('nx', real(c%grid%nx, dp), '-', is_integer=.true.)
        call r%add('ny', real(c%grid%ny, dp), '-', is_integer=.true.)
        call r%add('contact_modulus_pa', c%mat%e0_pa/(1.0_dp - c%mat%poisson**2), 'Pa')
        if (cfg%material%thickness_m > 0.0_dp) call r%add('layer_thickness_m', cfg%material%thickness_m, 'm')
        if (cfg%material%shift /= 'none') then
            call r%add('temperature_c', cfg%material%temperature_c, 'degC')
            call r%add('shift_factor', material_shift(cfg), '-')
        end if
        call r%add('speed_m_s', norm2(c%velocity_m_s), 'm/s')
        call r%add('velocity_direction_deg', cfg%motion%direction_deg, 'degree')
        call add_force_quantities(r, c%force_pa, c%slope_force_pa, c%velocity_m_s, cfg%motion%direction_deg, &
                                  cfg%load%mean_pressure_pa)
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
                real(dp) :: theta(cfg%analysis%n_theta)
                theta = [(pi*(j - 1)/cfg%analysis%n_theta, j = 1, cfg%analysis%n_theta)]
                call r%add_array('/anisotropy/band_q_per_m', c%band_q, '1/m')
                call r%add_array('/anisotropy/band_zeta', [cfg%analysis%zeta1, cfg%analysis%zeta2], '-')
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
            d = modulo(cfg%motion%direction_deg, 180.0_dp)
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
            call r%add('persson_friction_coefficient', c%persson%friction_coefficient, '-')
            call r%add('persson_lateral_force_ratio', c%persson%lateral_force_ratio, '-')
            call r%add_array('/persson/q_per_m', c%persson%q_per_m, '1/m')
            call r%add_array('/persson/area_fraction', c%persson%area_fraction, '-')
        end if
        call r%trim()
    end subroutine case_results

    !> The run summary a program prints, from the case's results `r` (one line per entry)
    function summary_lines(cfg, c, r) result(lines)
        type(config_t), intent(in) :: cfg
        type(case_t), intent(in) :: c
        type(results_t), intent(in) :: r
        character(len=summary_width), allocatable :: lines(:)
        character(len=summary_width) :: b
        real(dp) :: hrms
        hrms = r%get('rms_height_m')
        allocate (lines(0))
        lines = [lines, b_("veslide "//version_string()//": "//cfg%path//" -> "//cfg%output%file)]
        write (b, '(a,i0,a,i0,a,a,a,a,a,a)') "  grid ", c%grid%nx, " x ", c%grid%ny, &
            ", surface ", cfg%surface%kind, ", material ", cfg%material%model, ", kernel ", cfg%solver%kernel
        lines = [lines, b]
        if (c%grid%is_distributed()) then
            write (b, '(a,i0,a)') "  distributed over ", c%grid%ranks, " processes (rows of the grid)"
            lines = [lines, b]
        end if
        write (b, '(a,es12.5,a)') "  rms height            ", hrms, " m"; lines = [lines, b]
        write (b, '(a,es12.5,a)') "  nominal pressure      ", r%get('mean_pressure_pa'), " Pa"; lines = [lines, b]
        write (b, '(a,f12.8)') "  contact area fraction ", r%get('contact_area_fraction'); lines = [lines, b]
        write (b, '(a,es12.5,a,f9.5,a)') "  mean separation       ", r%get('mean_separation_m'), " m (", &
            r%get('mean_separation_m')/max(hrms, tiny(1.0_dp)), " h_rms)"
        lines = [lines, b]
        write (b, '(a,es12.5,a)') "  max pressure          ", r%get('max_pressure_pa'), " Pa"; lines = [lines, b]
        if (.not. c%kernel%symmetric) then
            write (b, '(a,es12.5)') "  friction coefficient  ", r%get('friction_coefficient'); lines = [lines, b]
            write (b, '(a,es12.5)') "  lateral force ratio   ", r%get('lateral_force_ratio'); lines = [lines, b]
        end if
        if (.not. c%mat%is_elastic()) then
            block
                real(dp) :: omega, td, qlo, qhi
                call c%mat%loss_peak(omega, td)
                qlo = c%grid%q0(); qhi = 0.5_dp*c%grid%nx*c%grid%q0()
                if (cfg%surface%kind == 'self_affine') then
                    qlo = cfg%surface%k_low*c%grid%q0(); qhi = cfg%surface%k_cut*c%grid%q0()
                end if
                write (b, '(a,f6.3,a,es10.3,a)') "  loss peak             tan(delta) = ", td, " at ", omega, " rad/s"
                lines = [lines, b]
                write (b, '(a,es9.3,a,es9.3,a,es9.3,a)') "    met by the surface's q for speeds ", omega/qhi, " to ", &
                    omega/qlo, " m/s (this run ", norm2(c%velocity_m_s), ")"
                lines = [lines, b]
            end block
        end if
        write (b, '(a,a,a,i0,a,i0,a,es9.2,a,l1)') "  solver ", c%state%method, ": ", c%state%iterations, &
            " iterations, ", c%state%operator_applications, " FFT pairs, residual ", c%state%residual, &
            ", converged ", c%state%converged
        lines = [lines, b]
        if (c%state%device == 'gpu') then
            block
                type(device_info_t) :: info
                type(error_t), allocatable :: none
                call device_info(info, none)
                if (.not. allocated(none)) then
                    write (b, '(a,f0.3,a)') "  solved on the GPU "//info%name//" (set-up and transfers ", &
                        c%state%transfer_seconds, " s)"
                    lines = [lines, b]
                end if
            end block
        end if
        write (b, '(a,f8.3,a,f8.3,a,f8.3,a)') "  time: surface ", r%get('surface_seconds'), " s, kernel ", &
            r%get('kernel_seconds'), " s, solve ", r%get('solve_seconds'), " s"
        lines = [lines, b]
    contains
        function b_(t) result(l)
            character(len=*), intent(in) :: t
            character(len=summary_width) :: l
            l = t
        end function b_
    end function summary_lines

    !> Write one case to an HDF5 file (the caller writes to a temporary name, then commits). On a
    !> distributed grid (collective): the fields are written by every process at once (parallel
    !> HDF5), then the first process adds everything else, so the file is laid out as a serial one.
    subroutine write_case(path, cfg, c, error)
        character(len=*), intent(in) :: path
        type(config_t), intent(in) :: cfg
        type(case_t), intent(in) :: c
        type(error_t), allocatable, intent(out) :: error
        type(h5file_t) :: f
        type(results_t) :: r
        if (c%grid%is_distributed()) then
            call case_results(cfg, c, r)                 ! (collective: global sums and extrema)
            call create_collective(f, path, c%grid, error)
            if (.not. allocated(error) .and. cfg%output%fields) call write_fields(error)
            if (allocated(error)) then
                call f%close()
            else
                call f%close(error)
            end if
            call share_error(c%grid, error); if (allocated(error)) return
            if (c%grid%is_root()) then
                call f%open(path, 'rw', error)
                if (.not. allocated(error)) call write_provenance(f, cfg%path, cfg%text, [cfg%surface%seed], error, &
                                  preparation=cfg%surface%preparation)
                if (.not. allocated(error)) call write_case_group(f, '', cfg, c, error, r)
                if (allocated(error)) then
                    call f%close()
                else
                    call f%close(error)
                end if
            end if
            call share_error(c%grid, error)
            return
        end if
        call f%open(path, 'w', error); if (allocated(error)) return
        call write_provenance(f, cfg%path, cfg%text, [cfg%surface%seed], error, &
                                  preparation=cfg%surface%preparation); if (allocated(error)) return
        call write_case_group(f, '', cfg, c, error); if (allocated(error)) return
        call f%close(error)
    contains
        subroutine write_fields(error)
            type(error_t), allocatable, intent(out) :: error
            call write_rows(f, c%grid, '/fields/height_m', c%h, error); if (allocated(error)) return
            call write_rows(f, c%grid, '/fields/pressure_pa', c%state%p, error); if (allocated(error)) return
            call write_rows(f, c%grid, '/fields/displacement_m', c%state%u, error); if (allocated(error)) return
            call write_rows(f, c%grid, '/fields/gap_m', c%state%g, error)
        end subroutine write_fields
    end subroutine write_case

    !> Results and fields of a case under `prefix` ('' for the root)
    subroutine write_case_group(f, prefix, cfg, c, error, r)
        type(h5file_t), intent(inout) :: f
        character(len=*), intent(in) :: prefix
        type(config_t), intent(in) :: cfg
        type(case_t), intent(in) :: c
        type(error_t), allocatable, intent(out) :: error
        !> the case's results, when the caller has them already
        type(results_t), intent(in), optional :: r
        type(results_t) :: r_
        if (present(r)) then
            r_ = r
        else
            call case_results(cfg, c, r_)
        end if
        call write_results(f, prefix, r_, error); if (allocated(error)) return
        call f%writeattr(prefix//'/scalars', 'solver_method', c%state%method, error); if (allocated(error)) return
        call f%writeattr(prefix//'/scalars', 'kernel_variant', cfg%solver%kernel, error); if (allocated(error)) return
        ! where it was solved ('cpu' or 'gpu'; the device itself: the root's provenance)
        call f%writeattr(prefix//'/scalars', 'device', c%state%device, error); if (allocated(error)) return
        if (c%state%device == 'gpu') then
            call f%writeattr(prefix//'/scalars', 'device_transfer_seconds', c%state%transfer_seconds, error)
            if (allocated(error)) return
        end if
        if (cfg%output%fields .and. c%grid%is_distributed()) then
            ! written already by every process (write_case): their attributes
            call field_attributes(prefix//'/fields/height_m', 'm'); if (allocated(error)) return
            call field_attributes(prefix//'/fields/pressure_pa', 'Pa'); if (allocated(error)) return
            call field_attributes(prefix//'/fields/displacement_m', 'm'); if (allocated(error)) return
            call field_attributes(prefix//'/fields/gap_m', 'm')
        else if (cfg%output%fields) then
            call write_field(f, prefix//'/fields/height_m', c%h, 'm', error); if (allocated(error)) return
            call write_field(f, prefix//'/fields/pressure_pa', c%state%p, 'Pa', error); if (allocated(error)) return
            call write_field(f, prefix//'/fields/displacement_m', c%state%u, 'm', error); if (allocated(error)) return
            call write_field(f, prefix//'/fields/gap_m', c%state%g, 'm', error)
        end if
    contains
        subroutine field_attributes(name, units)
            character(len=*), intent(in) :: name, units
            call f%writeattr(name, 'units', units, error); if (allocated(error)) return
            call f%writeattr(name, 'layout', field_layout, error)
        end subroutine field_attributes
    end subroutine write_case_group

end module veslide_case
