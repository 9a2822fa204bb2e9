!> One case from a configuration: surface, material, kernel, solve, derived quantities, HDF5 file.
module veslide_run
    use, intrinsic :: iso_c_binding, only: c_int, c_char, c_null_char
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use veslide_kinds, only: dp, i8, pi
    use veslide_error, only: error_t, fatal_error
    use veslide_config, only: config_t
    use veslide_fftw, only: fft2d_t
    use veslide_material, only: material_t, new_elastic, new_one_term, new_creep, new_relaxation
    use veslide_surface, only: psd_t, random_surface, cosine_surface, bisinusoid_surface, &
                               paraboloid_surface, cylinder_surface, rms_height
    use veslide_kernel, only: kernel_t, build_kernel, kernel_variant_id
    use veslide_solver, only: solver_options_t, contact_state_t, solve_contact
    use veslide_analysis, only: contact_area_fraction, mean_separation, tangential_force, slope_force
    use veslide_hdf5, only: h5file_t, hdf5_library_version
    use veslide_anisotropy, only: tensor_axes, decompose, m2_of_theta, patch_stats_t, contact_patches, percolates
    use veslide_surface, only: slope_tensor
    use veslide_version, only: version_string, compiler_string, compiler_flags, git_revision, utc_timestamp
    implicit none
    private
    public :: case_t, build_surface, build_material, run_case, write_case, prepare_output, &
              commit_output, discard_output, case_scalars, write_provenance, write_case_group, &
              build_case_kernel, solve_prepared, wall_seconds

    !> Everything one solve produced
    type :: case_t
        real(dp), allocatable :: h(:, :)          !! rigid heights [m]
        type(material_t) :: mat
        type(kernel_t) :: kernel
        type(contact_state_t) :: state
        real(dp) :: lx_m = 0.0_dp, ly_m = 0.0_dp
        real(dp) :: velocity_m_s(2) = 0.0_dp
        real(dp) :: force_pa(2) = 0.0_dp          !! <p grad w>, solid on rigid surface [Pa]
        real(dp) :: slope_force_pa(2) = 0.0_dp    !! <p grad h> [Pa] (check)
        real(dp) :: kernel_seconds = 0.0_dp, solve_seconds = 0.0_dp, surface_seconds = 0.0_dp
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
    end type case_t

    interface
        integer(c_int) function c_rename(old, new) bind(c, name='rename')
            import :: c_int, c_char
            character(kind=c_char), intent(in) :: old(*), new(*)
        end function c_rename
    end interface

contains

    real(dp) function wall_seconds() result(t)
        integer(i8) :: count, rate
        call system_clock(count, rate)
        t = real(count, dp)/real(rate, dp)
    end function wall_seconds

    !> Rigid heights from the configuration (may read a file, and then fills the grid and lengths)
    subroutine build_surface(cfg, fft, h, error)
        type(config_t), intent(inout) :: cfg
        type(fft2d_t), intent(inout) :: fft
        real(dp), allocatable, intent(out) :: h(:, :)
        type(error_t), allocatable, intent(out) :: error
        type(psd_t) :: psd
        real(dp) :: q0
        if (cfg%surface_kind == 'file') then
            call read_height_file(cfg, h, error); return
        end if
        allocate (h(cfg%nx, cfg%ny))
        select case (cfg%surface_kind)
        case ('self_affine')
            q0 = 2.0_dp*pi/cfg%lx_m
            psd = psd_t(hurst=cfg%hurst, eccentricity=cfg%eccentricity, alpha_rad=cfg%alpha_deg*pi/180.0_dp, &
                        q_low=cfg%k_low*q0, q_roll=cfg%k_roll*q0, q_cut=cfg%k_cut*q0)
            call random_surface(cfg%nx, cfg%ny, cfg%lx_m, cfg%ly_m, psd, cfg%seed, cfg%rms_slope, cfg%rms_height_m, &
                                h, error, &
                                realised=cfg%scale_to == 'realised')
            if (allocated(error)) error%message = "veslide: "//cfg%path//": &surface: "//error%message
        case ('cosine')
            call cosine_surface(cfg%nx, cfg%ny, cfg%lx_m, cfg%ly_m, cfg%amplitude_m, cfg%wavelength_m, &
                                cfg%direction_deg*pi/180.0_dp, h)
        case ('bisinusoid')
            call bisinusoid_surface(cfg%nx, cfg%ny, cfg%lx_m, cfg%ly_m, cfg%amplitude_m, cfg%wavelength_m, h)
        case ('paraboloid')
            call paraboloid_surface(cfg%nx, cfg%ny, cfg%lx_m, cfg%ly_m, cfg%radius_m, h)
        case ('cylinder')
            call cylinder_surface(cfg%nx, cfg%ny, cfg%lx_m, cfg%radius_m, h)
        case ('flat')
            h = 0.0_dp
        end select
    end subroutine build_surface

    !> Measured topography: a square 2-D float64 dataset of heights [m]
    subroutine read_height_file(cfg, h, error)
        type(config_t), intent(inout) :: cfg
        real(dp), allocatable, intent(out) :: h(:, :)
        type(error_t), allocatable, intent(out) :: error
        type(h5file_t) :: f
        integer(i8) :: dims(7)
        integer :: rank
        logical :: is_double, exists
        character(len=:), allocatable :: at
        real(dp) :: length
        at = "veslide: "//cfg%path//": &surface file '"//cfg%height_file//"': "
        inquire (file=cfg%height_file, exist=exists)
        if (.not. exists) then
            call fatal_error(error, at//"no such file"); return
        end if
        call f%open(cfg%height_file, 'r', error)
        if (allocated(error)) then
            error%message = at//"not a readable HDF5 file"; return
        end if
        call f%shape_of(cfg%height_dataset, dims, rank, is_double)
        if (rank < 0) then
            call fatal_error(error, at//"no dataset '"//cfg%height_dataset//"' (set &surface dataset)"); return
        end if
        if (rank /= 2 .or. .not. is_double .or. dims(1) /= dims(2) .or. dims(1) < 2) then
            call fatal_error(error, at//"dataset '"//cfg%height_dataset// &
                "' must be a square 2-D float64 array of heights in metres"); return
        end if
        allocate (h(dims(1), dims(2)))
        call f%read_r2(cfg%height_dataset, h, error)
        if (allocated(error)) return
        if (.not. all(ieee_is_finite(h))) then
            call fatal_error(error, at//"dataset '"//cfg%height_dataset//"' contains NaN or infinite heights"); return
        end if
        cfg%nx = int(dims(1)); cfg%ny = int(dims(2))
        if (cfg%lx_m == 0.0_dp) then
            if (.not. f%attr_exists(cfg%height_dataset, 'length_m')) then
                call fatal_error(error, at//"the cell side is unknown: set &grid lx_m or a 'length_m' attribute"); return
            end if
            call f%read_attr_r0(cfg%height_dataset, 'length_m', length, error)
            if (allocated(error)) return
            if (.not. (length > 0.0_dp .and. ieee_is_finite(length))) then
                call fatal_error(error, at//"attribute length_m must be > 0"); return
            end if
            cfg%lx_m = length
        end if
        cfg%ly_m = cfg%lx_m
        call f%close()
    end subroutine read_height_file

    !> The solid from &material
    subroutine build_material(cfg, mat, error)
        type(config_t), intent(in) :: cfg
        type(material_t), intent(out) :: mat
        type(error_t), allocatable, intent(out) :: error
        select case (cfg%model)
        case ('elastic')
            call new_elastic(mat, cfg%young_pa, cfg%poisson, error)
        case ('one_term')
            call new_one_term(mat, cfg%einf_pa, cfg%ratio, cfg%tau_s, cfg%poisson, error)
        case ('creep')
            call new_creep(mat, cfg%e0_pa, cfg%prony_coef, cfg%prony_time_s, cfg%poisson, error)
        case ('relaxation')
            call new_relaxation(mat, cfg%e0_pa, cfg%prony_coef, cfg%prony_time_s, cfg%poisson, error)
        end select
        if (allocated(error)) error%message = "veslide: "//cfg%path//": &material: "//error%message
    end subroutine build_material

    !> Build and solve one case
    subroutine run_case(cfg, c, error)
        type(config_t), intent(inout) :: cfg
        type(case_t), intent(out) :: c
        type(error_t), allocatable, intent(out) :: error
        type(fft2d_t) :: fft
        real(dp) :: t0

        t0 = wall_seconds()
        if (cfg%surface_kind == 'file') then
            call build_surface(cfg, fft, c%h, error); if (allocated(error)) return
            call fft%init(cfg%nx, cfg%ny, error, planner=cfg%fft_planner, nthreads=cfg%threads)
            if (allocated(error)) return
        else
            call fft%init(cfg%nx, cfg%ny, error, planner=cfg%fft_planner, nthreads=cfg%threads)
            if (allocated(error)) return
            call build_surface(cfg, fft, c%h, error); if (allocated(error)) return
        end if
        c%surface_seconds = wall_seconds() - t0
        call build_material(cfg, c%mat, error); if (allocated(error)) return
        call build_case_kernel(cfg, c%mat, c%kernel, c%kernel_seconds, error); if (allocated(error)) return
        call solve_prepared(cfg, fft, c, error)
        call fft%destroy()
    end subroutine run_case

    !> The kernel of the configuration's grid, material and velocity
    subroutine build_case_kernel(cfg, mat, kernel, seconds, error)
        type(config_t), intent(in) :: cfg
        type(material_t), intent(in) :: mat
        type(kernel_t), intent(out) :: kernel
        real(dp), intent(out) :: seconds
        type(error_t), allocatable, intent(out) :: error
        real(dp) :: t0, th
        t0 = wall_seconds()
        th = cfg%velocity_direction_deg*pi/180.0_dp
        call build_kernel(kernel, cfg%nx, cfg%ny, cfg%lx_m, cfg%ly_m, mat, cfg%speed_m_s*[cos(th), sin(th)], &
                          kernel_variant_id(cfg%kernel), error, alias_tol=cfg%alias_tol, alias_max=cfg%alias_max)
        if (allocated(error)) error%message = "veslide: "//cfg%path//": &solver kernel = '"//trim(cfg%kernel)// &
                                              "': "//error%message
        seconds = wall_seconds() - t0
    end subroutine build_case_kernel

    !> Solve a case whose heights, material and kernel are set, then derive its quantities;
    !> `p_init` warm-starts the solver (a speed sweep passes the previous speed's pressure)
    subroutine solve_prepared(cfg, fft, c, error, p_init, g_init)
        type(config_t), intent(in) :: cfg
        type(fft2d_t), intent(inout) :: fft
        type(case_t), intent(inout) :: c
        type(error_t), allocatable, intent(out) :: error
        real(dp), intent(in), optional :: p_init(:, :), g_init(:, :)
        type(solver_options_t) :: opts
        real(dp) :: t0
        c%lx_m = cfg%lx_m; c%ly_m = cfg%ly_m
        c%velocity_m_s = c%kernel%velocity_m_s
        opts%method = cfg%method
        opts%tolerance = cfg%tolerance
        opts%max_iterations = cfg%max_iterations
        opts%anderson_memory = cfg%anderson_memory
        opts%balance_every = cfg%balance_every
        opts%balance_ratio = cfg%balance_ratio
        opts%balance_factor = cfg%balance_factor
        t0 = wall_seconds()
        call solve_contact(c%kernel, fft, c%h, cfg%mean_pressure_pa, opts, c%state, error, p_init=p_init, &
                           g_init=g_init)
        if (allocated(error)) return
        c%solve_seconds = wall_seconds() - t0
        call tangential_force(c%kernel, fft, c%state%p, c%force_pa)
        call slope_force(fft, cfg%lx_m, cfg%ly_m, c%state%p, c%h, c%slope_force_pa)
        c%have_anisotropy = .false.; c%have_patches = .false.
        if (cfg%anisotropy) call anisotropy_analysis(cfg, fft, c)
        if (cfg%patches) then
            call contact_patches(c%state%p > 0.0_dp, cfg%lx_m, cfg%ly_m, c%patches)
            c%percolates_x = percolates(.not. (c%state%p > 0.0_dp), 1)
            c%percolates_y = percolates(.not. (c%state%p > 0.0_dp), 2)
            c%have_patches = .true.
        end if
    end subroutine solve_prepared

    !> Slope tensors of h and of the deformed surface w in the band [zeta1, zeta2] q0, and eq. (16)
    subroutine anisotropy_analysis(cfg, fft, c)
        type(config_t), intent(in) :: cfg
        type(fft2d_t), intent(inout) :: fft
        type(case_t), intent(inout) :: c
        real(dp) :: l1, l2, q0
        q0 = 2.0_dp*pi/cfg%lx_m
        c%band_q = [cfg%zeta1, cfg%zeta2]*q0
        call slope_tensor(fft, cfg%lx_m, cfg%ly_m, c%h, c%m_surface, band=c%band_q)
        call slope_tensor(fft, cfg%lx_m, cfg%ly_m, c%state%u, c%m_deformed, band=c%band_q)
        call tensor_axes(c%m_surface, l1, l2, c%theta_s); c%gamma_s = l2/l1
        call tensor_axes(c%m_deformed, l1, l2, c%theta_d); c%gamma_d = l2/l1
        call decompose(c%m_surface, c%m_deformed, cfg%iso_tol, c%sigma1, c%sigma2, c%phi)
        c%have_anisotropy = .true.
    end subroutine anisotropy_analysis

    !> Check that the result can be written, before any work: refuses an existing file unless
    !> `overwrite`, and creates (then removes) the temporary file it will write to
    subroutine prepare_output(path, overwrite, tmp, error)
        character(len=*), intent(in) :: path
        logical, intent(in) :: overwrite
        character(len=:), allocatable, intent(out) :: tmp
        type(error_t), allocatable, intent(out) :: error
        logical :: exists
        integer :: u, stat
        character(len=512) :: msg
        character(len=16) :: pid
        inquire (file=path, exist=exists)
        if (exists .and. .not. overwrite) then
            call fatal_error(error, "veslide: &output file '"//path//"' exists; "// &
                "set &output overwrite = .true. or pass --overwrite to replace it"); return
        end if
        write (pid, '(i0)') getpid()
        tmp = path//'.part-'//trim(pid)
        open (newunit=u, file=tmp, status='replace', action='write', iostat=stat, iomsg=msg)
        if (stat /= 0) then
            call fatal_error(error, "veslide: &output file '"//path//"' cannot be written: "//trim(msg)); return
        end if
        close (u, status='delete')
    end subroutine prepare_output

    !> Move the finished temporary file onto its final name
    subroutine commit_output(tmp, path, error)
        character(len=*), intent(in) :: tmp, path
        type(error_t), allocatable, intent(out) :: error
        if (c_rename(tmp//c_null_char, path//c_null_char) /= 0) &
            call fatal_error(error, "veslide: cannot rename '"//tmp//"' to '"//path//"'")
    end subroutine commit_output

    !> Remove a temporary file, if present
    subroutine discard_output(tmp)
        character(len=*), intent(in) :: tmp
        integer :: u, stat
        logical :: exists
        inquire (file=tmp, exist=exists)
        if (.not. exists) return
        open (newunit=u, file=tmp, status='old', iostat=stat)
        if (stat == 0) close (u, status='delete')
    end subroutine discard_output

    !> The scalar results of a case, in output order: names, units and values (integers included,
    !> flagged by is_int); the same list feeds /scalars and the sweep's summary table
    subroutine case_scalars(cfg, c, names, units, values, is_int)
        type(config_t), intent(in) :: cfg
        type(case_t), intent(in) :: c
        character(len=32), allocatable, intent(out) :: names(:)
        character(len=8), allocatable, intent(out) :: units(:)
        real(dp), allocatable, intent(out) :: values(:)
        logical, allocatable, intent(out) :: is_int(:)
        real(dp) :: vhat(2), fn, tang(2), lat(2)
        integer :: nn
        allocate (names(64), units(64), values(64), is_int(64))
        nn = 0
        fn = cfg%mean_pressure_pa
        vhat = [cos(cfg%velocity_direction_deg*pi/180.0_dp), sin(cfg%velocity_direction_deg*pi/180.0_dp)]
        lat = [-vhat(2), vhat(1)]
        tang = c%force_pa
        call add('contact_area_fraction', contact_area_fraction(c%state%p), '-')
        call add('mean_separation_m', mean_separation(c%state%g), 'm')
        call add('rms_height_m', rms_height(c%h), 'm')
        call add('max_pressure_pa', maxval(c%state%p), 'Pa')
        call add('mean_pressure_pa', fn, 'Pa')
        call add('approach_m', c%state%approach_m, 'm')
        call add('iterations', real(c%state%iterations, dp), '-', .true.)
        call add('operator_applications', real(c%state%operator_applications, dp), '-', .true.)
        call add('converged', merge(1.0_dp, 0.0_dp, c%state%converged), '-', .true.)
        call add('residual', c%state%residual, '-')
        call add('penetration', c%state%penetration, '-')
        call add('complementarity', c%state%complementarity, '-')
        call add('negative_pressure', c%state%negative_pressure, '-')
        call add('load_error', c%state%load_error, '-')
        call add('tolerance', cfg%tolerance, '-')
        call add('length_x_m', c%lx_m, 'm')
        call add('length_y_m', c%ly_m, 'm')
        call add('nx', real(size(c%h, 1), dp), '-', .true.)
        call add('ny', real(size(c%h, 2), dp), '-', .true.)
        call add('contact_modulus_pa', c%mat%e0_pa/(1.0_dp - c%mat%poisson**2), 'Pa')
        call add('speed_m_s', norm2(c%velocity_m_s), 'm/s')
        call add('velocity_direction_deg', cfg%velocity_direction_deg, 'degree')
        call add('friction_force_pa', -dot_product(tang, vhat), 'Pa')
        call add('friction_coefficient', -dot_product(tang, vhat)/fn, '-')
        call add('lateral_force_pa', dot_product(tang, lat), 'Pa')
        call add('lateral_force_ratio', dot_product(tang, lat)/fn, '-')
        call add('force_x_pa', tang(1), 'Pa')
        call add('force_y_pa', tang(2), 'Pa')
        call add('friction_coefficient_slope', -dot_product(c%slope_force_pa, vhat)/fn, '-')
        call add('dissipated_power_w_m2', -dot_product(tang, c%velocity_m_s), 'W/m^2')
        call add('kernel_alias_error', c%kernel%alias_error, '-')
        call add('kernel_alias_zones', real(c%kernel%alias_zones, dp), '-', .true.)
        call add('kernel_min_re_m_pa', c%kernel%min_re, 'm/Pa')
        call add('surface_seconds', c%surface_seconds, 's')
        call add('kernel_seconds', c%kernel_seconds, 's')
        call add('solve_seconds', c%solve_seconds, 's')
        if (c%have_anisotropy) then
            call add('gamma_s', c%gamma_s, '-'); call add('gamma_d', c%gamma_d, '-')
            call add('theta_s_rad', c%theta_s, 'rad'); call add('theta_d_rad', c%theta_d, 'rad')
            call add('sigma1', c%sigma1, '-'); call add('sigma2', c%sigma2, '-')
            call add('phi_rad', c%phi, 'rad')
        end if
        if (c%have_patches) then
            call add('patch_count', real(c%patches%count, dp), '-', .true.)
            call add('patch_mean_area_fraction', c%patches%mean_area_fraction, '-')
            call add('patch_gamma', c%patches%gamma, '-')
            call add('patch_theta_rad', c%patches%theta, 'rad')
            call add('percolates_x', merge(1.0_dp, 0.0_dp, c%percolates_x), '-', .true.)
            call add('percolates_y', merge(1.0_dp, 0.0_dp, c%percolates_y), '-', .true.)
            ! along and across v when v lies on a grid axis; -1 (undefined) otherwise
            block
                real(dp) :: along, across, d
                d = modulo(cfg%velocity_direction_deg, 180.0_dp)
                along = -1.0_dp; across = -1.0_dp
                if (d < 1.0e-9_dp .or. d > 180.0_dp - 1.0e-9_dp) then
                    along = merge(1.0_dp, 0.0_dp, c%percolates_x); across = merge(1.0_dp, 0.0_dp, c%percolates_y)
                else if (abs(d - 90.0_dp) < 1.0e-9_dp) then
                    along = merge(1.0_dp, 0.0_dp, c%percolates_y); across = merge(1.0_dp, 0.0_dp, c%percolates_x)
                end if
                call add('percolates_along_v', along, '-', .true.)
                call add('percolates_across_v', across, '-', .true.)
            end block
        end if
        names = names(1:nn); units = units(1:nn); values = values(1:nn); is_int = is_int(1:nn)
    contains
        subroutine add(name, value, unit, integer_valued)
            character(len=*), intent(in) :: name, unit
            real(dp), intent(in) :: value
            logical, intent(in), optional :: integer_valued
            nn = nn + 1
            names(nn) = name; units(nn) = unit; values(nn) = value; is_int(nn) = present(integer_valued)
        end subroutine add
    end subroutine case_scalars

    !> Root attributes of provenance and the input text
    subroutine write_provenance(f, cfg, error)
        type(h5file_t), intent(inout) :: f
        type(config_t), intent(in) :: cfg
        type(error_t), allocatable, intent(out) :: error
        character(len=32) :: seed_text
        call f%writeattr('/', 'veslide_version', version_string(), error); if (allocated(error)) return
        call f%writeattr('/', 'git_revision', git_revision(), error); if (allocated(error)) return
        call f%writeattr('/', 'compiler', compiler_string(), error); if (allocated(error)) return
        call f%writeattr('/', 'compiler_options', compiler_flags(), error); if (allocated(error)) return
        call f%writeattr('/', 'hdf5_version', hdf5_library_version(), error); if (allocated(error)) return
        call f%writeattr('/', 'created', utc_timestamp(), error); if (allocated(error)) return
        write (seed_text, '(i0)') cfg%seed
        call f%writeattr('/', 'seed', trim(seed_text), error); if (allocated(error)) return
        call f%writeattr('/', 'input_file', cfg%path, error); if (allocated(error)) return
        call f%write('/input/namelist', cfg%text, error); if (allocated(error)) return
        call f%writeattr('/input/namelist', 'units', '-', error)
    end subroutine write_provenance

    !> Write one case to an HDF5 file (the caller writes to a temporary name, then commits)
    subroutine write_case(path, cfg, c, error)
        character(len=*), intent(in) :: path
        type(config_t), intent(in) :: cfg
        type(case_t), intent(in) :: c
        type(error_t), allocatable, intent(out) :: error
        type(h5file_t) :: f
        call f%open(path, 'w', error); if (allocated(error)) return
        call write_provenance(f, cfg, error); if (allocated(error)) return
        call write_case_group(f, '', cfg, c, error); if (allocated(error)) return
        call f%close()
    end subroutine write_case

    !> Scalars, anisotropy, patches and fields of a case under `prefix` ('' for the root)
    subroutine write_case_group(f, prefix, cfg, c, error)
        type(h5file_t), intent(inout) :: f
        character(len=*), intent(in) :: prefix
        type(config_t), intent(in) :: cfg
        type(case_t), intent(in) :: c
        type(error_t), allocatable, intent(out) :: error
        character(len=*), parameter :: layout = "Fortran order (nx, ny): h5py shape (ny, nx), index [iy, ix]"
        character(len=32), allocatable :: names(:)
        character(len=8), allocatable :: units(:)
        real(dp), allocatable :: values(:)
        logical, allocatable :: is_int(:)
        integer :: k

        call case_scalars(cfg, c, names, units, values, is_int)
        do k = 1, size(names)
            if (is_int(k)) then
                call f%write(prefix//'/scalars/'//trim(names(k)), nint(values(k)), error)
            else
                call f%write(prefix//'/scalars/'//trim(names(k)), values(k), error)
            end if
            if (allocated(error)) return
            call f%writeattr(prefix//'/scalars/'//trim(names(k)), 'units', trim(units(k)), error)
            if (allocated(error)) return
        end do
        call f%writeattr(prefix//'/scalars', 'solver_method', c%state%method, error); if (allocated(error)) return
        call f%writeattr(prefix//'/scalars', 'kernel_variant', trim(cfg%kernel), error); if (allocated(error)) return

        if (c%have_anisotropy) then
            block
                real(dp) :: theta(cfg%n_theta)
                integer :: j
                theta = [(pi*(j - 1)/cfg%n_theta, j = 1, cfg%n_theta)]
                call array('/anisotropy/band_q_per_m', c%band_q, '1/m')
                call array('/anisotropy/band_zeta', [cfg%zeta1, cfg%zeta2], '-')
                call array('/anisotropy/surface_tensor', reshape(c%m_surface, [4]), '-')
                call array('/anisotropy/deformed_tensor', reshape(c%m_deformed, [4]), '-')
                call array('/anisotropy/theta_rad', theta, 'rad')
                call array('/anisotropy/m2_surface', m2_of_theta(c%m_surface, theta), '-')
                call array('/anisotropy/mu2_deformed', m2_of_theta(c%m_deformed, theta), '-')
                if (allocated(error)) return
                call f%writeattr(prefix//'/anisotropy/surface_tensor', 'layout', '[M11, M21, M12, M22]', error)
                if (allocated(error)) return
                call f%writeattr(prefix//'/anisotropy/deformed_tensor', 'layout', '[M11, M21, M12, M22]', error)
                if (allocated(error)) return
            end block
        end if
        if (c%have_patches) then
            call array('/patches/orientation_tensor', reshape(c%patches%orientation, [4]), '-')
            if (allocated(error)) return
        end if
        if (cfg%write_fields) then
            call field('height_m', c%h, 'm')
            call field('pressure_pa', c%state%p, 'Pa')
            call field('displacement_m', c%state%u, 'm')
            call field('gap_m', c%state%g, 'm')
        end if

    contains

        subroutine array(name, value, unit)
            character(len=*), intent(in) :: name, unit
            real(dp), intent(in) :: value(:)
            if (allocated(error)) return
            call f%write(prefix//name, value, error); if (allocated(error)) return
            call f%writeattr(prefix//name, 'units', unit, error)
        end subroutine array

        subroutine field(name, value, unit)
            character(len=*), intent(in) :: name, unit
            real(dp), intent(in) :: value(:, :)
            if (allocated(error)) return
            call f%write(prefix//'/fields/'//name, value, error); if (allocated(error)) return
            call f%writeattr(prefix//'/fields/'//name, 'units', unit, error); if (allocated(error)) return
            call f%writeattr(prefix//'/fields/'//name, 'layout', layout, error)
        end subroutine field

    end subroutine write_case_group

end module veslide_run
