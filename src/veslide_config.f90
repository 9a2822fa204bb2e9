!> The namelist input: groups &grid, &surface, &material, &load, &motion, &solver, &output.
!>
!> Every group is optional (defaults apply); every value is range-checked, and a failure is an
!> `error_t` whose message names the file, the group, the variable and the allowed range.
module veslide_config
    use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
    use veslide_kinds, only: dp, i8
    use veslide_error, only: error_t, fatal_error
    implicit none
    private
    public :: config_t, read_config, read_text_file, max_prony

    integer, parameter :: max_prony = 64
    real(dp), parameter :: unset = -huge(1.0_dp)

    type :: config_t
        character(len=:), allocatable :: path        !! namelist file
        character(len=:), allocatable :: text        !! its text, verbatim
        ! &grid
        integer :: nx = 256, ny = 256
        real(dp) :: lx_m = 0.0_dp, ly_m = 0.0_dp
        ! &surface
        character(len=32) :: surface_kind = 'self_affine'
        integer(i8) :: seed = 1_i8
        real(dp) :: hurst = 0.8_dp, eccentricity = 1.0_dp, alpha_deg = 0.0_dp
        real(dp) :: k_low = 1.0_dp, k_roll = 1.0_dp, k_cut = 64.0_dp
        real(dp) :: rms_slope = 0.025_dp, rms_height_m = 0.0_dp
        character(len=16) :: scale_to = 'realised'
        real(dp) :: amplitude_m = 0.0_dp, wavelength_m = 0.0_dp, direction_deg = 0.0_dp, radius_m = 0.0_dp
        character(len=:), allocatable :: height_file, height_dataset
        ! &material
        character(len=16) :: model = 'elastic'
        real(dp) :: young_pa = 1.0e7_dp, poisson = 0.5_dp
        real(dp) :: einf_pa = 1.0e8_dp, ratio = 11.0_dp, tau_s = 1.0e-2_dp, e0_pa = 0.0_dp
        real(dp), allocatable :: prony_coef(:), prony_time_s(:)
        ! &load
        real(dp) :: mean_pressure_pa = 32.0e3_dp
        ! &motion
        real(dp) :: speed_m_s = 0.0_dp, velocity_direction_deg = 0.0_dp
        ! &solver
        character(len=16) :: method = 'auto', fft_planner = 'measure'
        character(len=24) :: kernel = 'spectral'
        real(dp) :: tolerance = 1.0e-10_dp, alias_tol = 1.0e-6_dp
        integer :: max_iterations = 20000, alias_max = 64, threads = 1
        integer :: anderson_memory = 5, balance_every = 50
        real(dp) :: balance_ratio = 10.0_dp, balance_factor = 3.0_dp
        ! &analysis
        logical :: anisotropy = .false., patches = .false.
        real(dp) :: zeta1 = 1.0_dp, zeta2 = 0.0_dp, iso_tol = 1.0e-3_dp
        integer :: n_theta = 72
        ! &sweep (lists; an empty list keeps the single value of its group)
        logical :: is_sweep = .false.
        logical :: sweep_warm_start = .true.
        real(dp), allocatable :: sweep_speeds(:), sweep_alphas(:), sweep_eccs(:), sweep_pressures(:)
        integer(i8), allocatable :: sweep_seeds(:)
        ! &output
        character(len=:), allocatable :: output_file
        logical :: write_fields = .true., overwrite = .false.
    end type config_t

contains

    !> Whole text of a file
    subroutine read_text_file(path, text, error)
        character(len=*), intent(in) :: path
        character(len=:), allocatable, intent(out) :: text
        type(error_t), allocatable, intent(out) :: error
        integer :: u, stat, n
        character(len=512) :: msg
        logical :: exists
        inquire (file=path, exist=exists, size=n)
        if (.not. exists) then
            call fatal_error(error, "veslide: cannot open '"//path//"': no such file"); return
        end if
        open (newunit=u, file=path, access='stream', form='unformatted', status='old', action='read', &
              iostat=stat, iomsg=msg)
        if (stat /= 0) then
            call fatal_error(error, "veslide: cannot open '"//path//"': "//trim(msg)); return
        end if
        allocate (character(len=max(n, 0)) :: text)
        if (n > 0) read (u, iostat=stat, iomsg=msg) text
        close (u)
        if (stat /= 0) call fatal_error(error, "veslide: cannot read '"//path//"': "//trim(msg))
    end subroutine read_text_file

    !> Read and check a namelist file
    subroutine read_config(path, cfg, error)
        character(len=*), intent(in) :: path
        type(config_t), intent(out) :: cfg
        type(error_t), allocatable, intent(out) :: error
        integer :: u, stat, k
        character(len=512) :: msg

        ! namelist variables (local copies carrying the defaults)
        integer :: nx, ny
        real(dp) :: lx_m, ly_m
        character(len=32) :: kind
        integer(i8) :: seed
        real(dp) :: hurst, eccentricity, alpha_deg, k_low, k_roll, k_cut, rms_slope, rms_height_m
        character(len=16) :: scale_to
        real(dp) :: amplitude_m, wavelength_m, direction_deg, radius_m
        character(len=1024) :: file, dataset
        character(len=16) :: model
        real(dp) :: young_pa, poisson, einf_pa, ratio, tau_s, e0_pa
        real(dp) :: creep_c_per_pa(max_prony), creep_tau_s(max_prony), relax_e_pa(max_prony), relax_rho_s(max_prony)
        real(dp) :: mean_pressure_pa, speed_m_s
        character(len=16) :: method, fft_planner
        character(len=24) :: kernel
        real(dp) :: tolerance, alias_tol
        integer :: max_iterations, alias_max, threads, anderson_memory, balance_every
        real(dp) :: balance_ratio, balance_factor
        logical :: fields, overwrite, anisotropy, patches
        real(dp) :: zeta1, zeta2, iso_tol
        integer :: n_theta
        real(dp) :: speeds_m_s(max_prony), alphas_deg(max_prony), eccentricities(max_prony), pressures_pa(max_prony)
        real(dp) :: speed_min_m_s, speed_max_m_s
        integer :: n_speeds, n_seeds
        integer(i8) :: seeds(max_prony)
        logical :: warm_start

        namelist /grid/ nx, ny, lx_m, ly_m
        namelist /surface/ kind, seed, hurst, eccentricity, alpha_deg, k_low, k_roll, k_cut, rms_slope, &
            rms_height_m, scale_to, amplitude_m, wavelength_m, direction_deg, radius_m, file, dataset
        namelist /material/ model, young_pa, poisson, einf_pa, ratio, tau_s, e0_pa, creep_c_per_pa, creep_tau_s, &
            relax_e_pa, relax_rho_s
        namelist /load/ mean_pressure_pa
        namelist /motion/ speed_m_s, direction_deg
        namelist /solver/ method, tolerance, max_iterations, kernel, alias_tol, alias_max, fft_planner, threads, &
            anderson_memory, balance_every, balance_ratio, balance_factor
        namelist /output/ file, fields, overwrite
        namelist /analysis/ anisotropy, zeta1, zeta2, n_theta, iso_tol, patches
        namelist /sweep/ speeds_m_s, speed_min_m_s, speed_max_m_s, n_speeds, alphas_deg, eccentricities, &
            pressures_pa, seeds, n_seeds, warm_start

        cfg%path = path
        call read_text_file(path, cfg%text, error); if (allocated(error)) return
        call check_group_names(path, cfg%text, error); if (allocated(error)) return
        open (newunit=u, file=path, status='old', action='read', iostat=stat, iomsg=msg)
        if (stat /= 0) then
            call fatal_error(error, "veslide: cannot open '"//path//"': "//trim(msg)); return
        end if

        ! &grid
        nx = cfg%nx; ny = cfg%ny; lx_m = cfg%lx_m; ly_m = cfg%ly_m
        rewind (u); read (u, nml=grid, iostat=stat, iomsg=msg)
        if (bad_read('grid')) return
        cfg%nx = nx; cfg%ny = ny; cfg%lx_m = lx_m; cfg%ly_m = ly_m

        ! &surface
        kind = cfg%surface_kind; seed = cfg%seed; hurst = cfg%hurst; eccentricity = cfg%eccentricity
        alpha_deg = cfg%alpha_deg; k_low = cfg%k_low; k_roll = cfg%k_roll; k_cut = cfg%k_cut
        rms_slope = cfg%rms_slope; rms_height_m = cfg%rms_height_m; scale_to = cfg%scale_to
        amplitude_m = cfg%amplitude_m; wavelength_m = cfg%wavelength_m; direction_deg = cfg%direction_deg
        radius_m = cfg%radius_m; file = ''; dataset = '/height_m'
        rewind (u); read (u, nml=surface, iostat=stat, iomsg=msg)
        if (bad_read('surface')) return
        cfg%surface_kind = kind; cfg%seed = seed; cfg%hurst = hurst; cfg%eccentricity = eccentricity
        cfg%alpha_deg = alpha_deg; cfg%k_low = k_low; cfg%k_roll = k_roll; cfg%k_cut = k_cut
        cfg%rms_slope = rms_slope; cfg%rms_height_m = rms_height_m; cfg%scale_to = scale_to
        cfg%amplitude_m = amplitude_m; cfg%wavelength_m = wavelength_m; cfg%direction_deg = direction_deg
        cfg%radius_m = radius_m; cfg%height_file = trim(file); cfg%height_dataset = trim(dataset)

        ! &material
        model = cfg%model; young_pa = cfg%young_pa; poisson = cfg%poisson; einf_pa = cfg%einf_pa
        ratio = cfg%ratio; tau_s = cfg%tau_s; e0_pa = cfg%e0_pa
        creep_c_per_pa = unset; creep_tau_s = unset; relax_e_pa = unset; relax_rho_s = unset
        rewind (u); read (u, nml=material, iostat=stat, iomsg=msg)
        if (bad_read('material')) return
        cfg%model = model; cfg%young_pa = young_pa; cfg%poisson = poisson; cfg%einf_pa = einf_pa
        cfg%ratio = ratio; cfg%tau_s = tau_s; cfg%e0_pa = e0_pa
        select case (model)
        case ('creep')
            call take_series('creep_c_per_pa', creep_c_per_pa, 'creep_tau_s', creep_tau_s)
        case ('relaxation')
            call take_series('relax_e_pa', relax_e_pa, 'relax_rho_s', relax_rho_s)
        case default
            allocate (cfg%prony_coef(0), cfg%prony_time_s(0))
        end select
        if (allocated(error)) return

        ! &load
        mean_pressure_pa = cfg%mean_pressure_pa
        rewind (u); read (u, nml=load, iostat=stat, iomsg=msg)
        if (bad_read('load')) return
        cfg%mean_pressure_pa = mean_pressure_pa

        ! &motion
        speed_m_s = cfg%speed_m_s; direction_deg = cfg%velocity_direction_deg
        rewind (u); read (u, nml=motion, iostat=stat, iomsg=msg)
        if (bad_read('motion')) return
        cfg%speed_m_s = speed_m_s; cfg%velocity_direction_deg = direction_deg

        ! &solver
        method = cfg%method; tolerance = cfg%tolerance; max_iterations = cfg%max_iterations
        kernel = cfg%kernel; alias_tol = cfg%alias_tol; alias_max = cfg%alias_max
        fft_planner = cfg%fft_planner; threads = cfg%threads
        anderson_memory = cfg%anderson_memory; balance_every = cfg%balance_every
        balance_ratio = cfg%balance_ratio; balance_factor = cfg%balance_factor
        rewind (u); read (u, nml=solver, iostat=stat, iomsg=msg)
        if (bad_read('solver')) return
        cfg%method = method; cfg%tolerance = tolerance; cfg%max_iterations = max_iterations
        cfg%kernel = kernel; cfg%alias_tol = alias_tol; cfg%alias_max = alias_max
        cfg%fft_planner = fft_planner; cfg%threads = threads
        cfg%anderson_memory = anderson_memory; cfg%balance_every = balance_every
        cfg%balance_ratio = balance_ratio; cfg%balance_factor = balance_factor

        ! &analysis
        anisotropy = cfg%anisotropy; zeta1 = cfg%zeta1; zeta2 = cfg%zeta2; n_theta = cfg%n_theta
        iso_tol = cfg%iso_tol; patches = cfg%patches
        rewind (u); read (u, nml=analysis, iostat=stat, iomsg=msg)
        if (bad_read('analysis')) return
        cfg%anisotropy = anisotropy; cfg%zeta1 = zeta1; cfg%zeta2 = zeta2; cfg%n_theta = n_theta
        cfg%iso_tol = iso_tol; cfg%patches = patches

        ! &sweep
        speeds_m_s = unset; alphas_deg = unset; eccentricities = unset; pressures_pa = unset
        seeds = -huge(1_i8); speed_min_m_s = 0; speed_max_m_s = 0; n_speeds = 0; n_seeds = 0
        warm_start = cfg%sweep_warm_start
        rewind (u); read (u, nml=sweep, iostat=stat, iomsg=msg)
        if (bad_read('sweep')) return
        cfg%sweep_warm_start = warm_start
        cfg%sweep_speeds = pack(speeds_m_s, speeds_m_s /= unset)
        cfg%sweep_alphas = pack(alphas_deg, alphas_deg /= unset)
        cfg%sweep_eccs = pack(eccentricities, eccentricities /= unset)
        cfg%sweep_pressures = pack(pressures_pa, pressures_pa /= unset)
        cfg%sweep_seeds = pack(seeds, seeds /= -huge(1_i8))
        if (n_speeds /= 0) then
            if (size(cfg%sweep_speeds) > 0 .or. n_speeds < 2 .or. n_speeds > 1000 .or. &
                .not. (speed_min_m_s > 0.0_dp .and. speed_max_m_s > speed_min_m_s)) then
                close (u)
                call fatal_error(error, "veslide: "//path//": &sweep n_speeds, speed_min_m_s, speed_max_m_s"// &
                    " are out of range (allowed: 2 <= n_speeds <= 1000, 0 < speed_min_m_s < speed_max_m_s,"// &
                    " and no speeds_m_s list)"); return
            end if
            cfg%sweep_speeds = [(speed_min_m_s*(speed_max_m_s/speed_min_m_s)**(real(k, dp)/(n_speeds - 1)), &
                                 k = 0, n_speeds - 1)]
        end if
        if (n_seeds /= 0) then
            if (size(cfg%sweep_seeds) > 0 .or. n_seeds < 1 .or. n_seeds > 100000) then
                close (u)
                call fatal_error(error, "veslide: "//path//": &sweep n_seeds = "//ival(n_seeds)// &
                    " is out of range (allowed: 1 to 100000, and no seeds list); seeds are seed, seed+1, ..."); return
            end if
            cfg%sweep_seeds = [(cfg%seed + k, k = 0, n_seeds - 1)]
        end if
        cfg%is_sweep = size(cfg%sweep_speeds) + size(cfg%sweep_alphas) + size(cfg%sweep_eccs) + &
                       size(cfg%sweep_pressures) + size(cfg%sweep_seeds) > 0

        ! &output
        file = 'veslide.h5'; fields = cfg%write_fields; overwrite = cfg%overwrite
        rewind (u); read (u, nml=output, iostat=stat, iomsg=msg)
        if (bad_read('output')) return
        cfg%output_file = trim(file); cfg%write_fields = fields; cfg%overwrite = overwrite
        close (u)

        call check_config(cfg, error)

    contains

        !> .true. (and error set) when the read failed other than by the group being absent
        logical function bad_read(group) result(bad)
            character(len=*), intent(in) :: group
            bad = .false.
            if (is_iostat_end(stat)) then
                stat = 0; return        ! group absent: defaults
            end if
            if (stat /= 0) then
                bad = .true.
                close (u)
                call fatal_error(error, "veslide: "//path//": &"//group//": "//trim(msg)// &
                    " (check the variable names and values of &"//group//")")
            end if
        end function bad_read

        subroutine take_series(name_c, c, name_t, t)
            character(len=*), intent(in) :: name_c, name_t
            real(dp), intent(in) :: c(:), t(:)
            integer :: nc, nt
            nc = count(c /= unset); nt = count(t /= unset)
            if (nc == 0 .or. nc /= nt .or. any(c(1:nc) == unset) .or. any(t(1:nt) == unset)) then
                call fatal_error(error, "veslide: "//path//": &material: "//name_c//" and "//name_t// &
                    " must list the same number (1 to 64) of terms, without gaps"); return
            end if
            cfg%prony_coef = c(1:nc); cfg%prony_time_s = t(1:nt)
        end subroutine take_series

    end subroutine read_config

    !> Every '&name' that opens a group must be one veslide reads (a misspelt group would be
    !> skipped silently by the namelist reads); comments and quoted strings are ignored
    subroutine check_group_names(path, text, error)
        character(len=*), intent(in) :: path, text
        type(error_t), allocatable, intent(out) :: error
        character(len=*), parameter :: known(9) = [character(len=8) :: 'grid', 'surface', 'material', 'load', &
                                                   'motion', 'solver', 'analysis', 'sweep', 'output']
        character(len=1) :: quote
        integer :: i, j
        logical :: comment
        quote = ' '; comment = .false.
        i = 1
        do while (i <= len(text))
            if (text(i:i) == new_line('a')) then
                comment = .false.
            else if (comment) then
                continue
            else if (quote /= ' ') then
                if (text(i:i) == quote) quote = ' '
            else if (text(i:i) == '"' .or. text(i:i) == "'") then
                quote = text(i:i)
            else if (text(i:i) == '!') then
                comment = .true.
            else if (text(i:i) == '&') then
                j = i + 1
                do while (j <= len(text))
                    if (index('abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_', text(j:j)) == 0) exit
                    j = j + 1
                end do
                if (j > i + 1) then
                    if (all(lower(text(i + 1:j - 1)) /= known) .and. lower(text(i + 1:j - 1)) /= 'end') then
                        call fatal_error(error, "veslide: "//path//": unknown namelist group &"//text(i + 1:j - 1)// &
                            " (known: &grid, &surface, &material, &load, &motion, &solver, &analysis, &sweep,"// &
                            " &output)"); return
                    end if
                end if
                i = j - 1
            end if
            i = i + 1
        end do
    contains
        pure function lower(s) result(t)
            character(len=*), intent(in) :: s
            character(len=len(s)) :: t
            integer :: k
            t = s
            do k = 1, len(s)
                if (s(k:k) >= 'A' .and. s(k:k) <= 'Z') t(k:k) = achar(iachar(s(k:k)) + 32)
            end do
        end function lower
    end subroutine check_group_names

    !> Range checks; messages name group, variable and allowed range
    subroutine check_config(cfg, error)
        type(config_t), intent(inout) :: cfg
        type(error_t), allocatable, intent(out) :: error
        character(len=:), allocatable :: at
        real(dp) :: big
        at = "veslide: "//cfg%path//": "
        big = huge(1.0_dp)

        if (cfg%nx < 1 .or. cfg%nx > 65536) then
            call fail("&grid nx", ival(cfg%nx), "1 to 65536"); return
        end if
        if (cfg%ny < 1 .or. cfg%ny > 65536) then
            call fail("&grid ny", ival(cfg%ny), "1 to 65536"); return
        end if
        if (cfg%nx*int(cfg%ny, i8) < 2) then
            call fail("&grid nx*ny", ival(cfg%nx*cfg%ny), "at least 2 cells"); return
        end if
        if (.not. ieee_is_finite(cfg%lx_m) .or. cfg%lx_m < 0.0_dp) then
            call fail("&grid lx_m", rval(cfg%lx_m), "> 0 [m], or 0 for the default (0.01, or the file's length_m)")
            return
        end if
        if (.not. ieee_is_finite(cfg%ly_m) .or. cfg%ly_m < 0.0_dp) then
            call fail("&grid ly_m", rval(cfg%ly_m), "> 0 [m], or 0 for lx_m*ny/nx"); return
        end if
        if (cfg%surface_kind /= 'file') call default_lengths(cfg, 0.01_dp)

        select case (cfg%surface_kind)
        case ('self_affine')
            if (.not. (cfg%hurst > 0.0_dp .and. cfg%hurst < 1.0_dp)) then
                call fail("&surface hurst", rval(cfg%hurst), "0 < hurst < 1"); return
            end if
            if (.not. (cfg%eccentricity > 0.0_dp .and. cfg%eccentricity <= 1.0_dp)) then
                call fail("&surface eccentricity", rval(cfg%eccentricity), "0 < eccentricity <= 1"); return
            end if
            if (.not. (abs(cfg%alpha_deg) <= 360.0_dp)) then
                call fail("&surface alpha_deg", rval(cfg%alpha_deg), "-360 to 360 [degrees]"); return
            end if
            if (.not. (cfg%k_low > 0.0_dp)) then
                call fail("&surface k_low", rval(cfg%k_low), "> 0 (multiples of 2 pi/lx_m)"); return
            end if
            if (.not. (cfg%k_roll >= cfg%k_low)) then
                call fail("&surface k_roll", rval(cfg%k_roll), ">= k_low"); return
            end if
            if (.not. (cfg%k_cut >= cfg%k_roll .and. cfg%k_cut < 0.5_dp*min(real(cfg%nx, dp), &
                                                    cfg%ny*cfg%lx_m/cfg%ly_m))) then
                call fail("&surface k_cut", rval(cfg%k_cut), ">= k_roll and below the Nyquist wavenumber "// &
                    rval(0.5_dp*min(real(cfg%nx, dp), cfg%ny*cfg%lx_m/cfg%ly_m))//" of the grid"); return
            end if
            if (.not. (cfg%rms_slope >= 0.0_dp .and. cfg%rms_slope < big .and. cfg%rms_height_m >= 0.0_dp &
                       .and. cfg%rms_height_m < big) .or. (cfg%rms_slope > 0.0_dp .eqv. cfg%rms_height_m > 0.0_dp)) then
                call fail("&surface rms_slope/rms_height_m", rval(cfg%rms_slope)//"/"//rval(cfg%rms_height_m), &
                    "exactly one of them > 0"); return
            end if
            if (cfg%scale_to /= 'realised' .and. cfg%scale_to /= 'expected') then
                call fail("&surface scale_to", "'"//trim(cfg%scale_to)//"'", "'realised' or 'expected'"); return
            end if
        case ('cosine', 'bisinusoid')
            if (.not. (cfg%amplitude_m > 0.0_dp .and. cfg%amplitude_m < big)) then
                call fail("&surface amplitude_m", rval(cfg%amplitude_m), "> 0 [m]"); return
            end if
            if (.not. (cfg%wavelength_m > 0.0_dp .and. cfg%wavelength_m < big)) then
                call fail("&surface wavelength_m", rval(cfg%wavelength_m), "> 0 [m]"); return
            end if
            if (.not. periodic_wave(cfg)) then
                call fail("&surface wavelength_m/direction_deg", rval(cfg%wavelength_m)//"/"//rval(cfg%direction_deg), &
                    "a wave periodic on the cell: lx_m*cos(direction)/wavelength_m and "// &
                    "ly_m*sin(direction)/wavelength_m whole numbers below nx/2, ny/2"); return
            end if
        case ('paraboloid', 'cylinder')
            if (.not. (cfg%radius_m > 0.0_dp .and. cfg%radius_m < big)) then
                call fail("&surface radius_m", rval(cfg%radius_m), "> 0 [m]"); return
            end if
        case ('flat')
        case ('file')
            if (len(cfg%height_file) == 0) then
                call fail("&surface file", "''", "the path of an HDF5 file of heights"); return
            end if
        case default
            call fail("&surface kind", "'"//trim(cfg%surface_kind)//"'", &
                "'self_affine', 'cosine', 'bisinusoid', 'paraboloid', 'cylinder', 'flat' or 'file'"); return
        end select

        if (.not. (cfg%poisson >= 0.0_dp .and. cfg%poisson <= 0.5_dp)) then
            call fail("&material poisson", rval(cfg%poisson), "0 to 0.5"); return
        end if
        select case (cfg%model)
        case ('elastic')
            if (.not. (cfg%young_pa > 0.0_dp .and. cfg%young_pa < big)) then
                call fail("&material young_pa", rval(cfg%young_pa), "> 0 [Pa]"); return
            end if
        case ('one_term')
            if (.not. (cfg%einf_pa > 0.0_dp .and. cfg%einf_pa < big)) then
                call fail("&material einf_pa", rval(cfg%einf_pa), "> 0 [Pa]"); return
            end if
            if (.not. (cfg%ratio > 1.0_dp .and. cfg%ratio < big)) then
                call fail("&material ratio", rval(cfg%ratio), "> 1 (Einf/E0)"); return
            end if
            if (.not. (cfg%tau_s > 0.0_dp .and. cfg%tau_s < big)) then
                call fail("&material tau_s", rval(cfg%tau_s), "> 0 [s]"); return
            end if
        case ('creep', 'relaxation')
            if (.not. (cfg%e0_pa > 0.0_dp .and. cfg%e0_pa < big)) then
                call fail("&material e0_pa", rval(cfg%e0_pa), "> 0 [Pa]"); return
            end if
            if (any(.not. (cfg%prony_coef > 0.0_dp)) .or. any(.not. (cfg%prony_time_s > 0.0_dp))) then
                call fail("&material Prony terms", "", "every coefficient and time > 0"); return
            end if
            if (cfg%model == 'creep' .and. .not. (sum(cfg%prony_coef) < 1.0_dp/cfg%e0_pa)) then
                call fail("&material creep_c_per_pa", "sum "//rval(sum(cfg%prony_coef)), &
                    "sum below 1/e0_pa = "//rval(1.0_dp/cfg%e0_pa)//" (so that Einf > E0)"); return
            end if
        case default
            call fail("&material model", "'"//trim(cfg%model)//"'", "'elastic', 'one_term', 'creep' or 'relaxation'")
            return
        end select

        if (.not. (cfg%mean_pressure_pa > 0.0_dp .and. cfg%mean_pressure_pa < big)) then
            call fail("&load mean_pressure_pa", rval(cfg%mean_pressure_pa), "> 0 [Pa]"); return
        end if
        if (.not. (cfg%speed_m_s >= 0.0_dp .and. cfg%speed_m_s < big)) then
            call fail("&motion speed_m_s", rval(cfg%speed_m_s), ">= 0 [m/s]"); return
        end if
        if (.not. (abs(cfg%velocity_direction_deg) <= 360.0_dp)) then
            call fail("&motion direction_deg", rval(cfg%velocity_direction_deg), "-360 to 360 [degrees]"); return
        end if

        if (all(cfg%method /= [character(len=16) :: 'auto', 'pk', 'dr'])) then
            call fail("&solver method", "'"//trim(cfg%method)//"'", "'auto', 'pk' or 'dr'"); return
        end if
        if (cfg%method == 'pk' .and. cfg%model /= 'elastic' .and. cfg%speed_m_s > 0.0_dp) then
            call fail("&solver method", "'pk'", "'auto' or 'dr' for a viscoelastic solid in motion "// &
                "(the operator is not symmetric)"); return
        end if
        if (.not. (cfg%tolerance >= 1.0e-15_dp .and. cfg%tolerance <= 1.0e-2_dp)) then
            call fail("&solver tolerance", rval(cfg%tolerance), "1e-15 to 1e-2"); return
        end if
        if (cfg%max_iterations < 1 .or. cfg%max_iterations > 10000000) then
            call fail("&solver max_iterations", ival(cfg%max_iterations), "1 to 10000000"); return
        end if
        if (all(cfg%kernel /= [character(len=17) :: 'spectral', 'collocation', 'collocation-alias', 'galerkin'])) then
            call fail("&solver kernel", "'"//trim(cfg%kernel)//"'", &
                "'spectral', 'collocation', 'collocation-alias' or 'galerkin'"); return
        end if
        if (.not. (cfg%alias_tol > 0.0_dp .and. cfg%alias_tol <= 0.1_dp)) then
            call fail("&solver alias_tol", rval(cfg%alias_tol), "0 < alias_tol <= 0.1"); return
        end if
        if (cfg%alias_max < 2 .or. cfg%alias_max > 1024) then
            call fail("&solver alias_max", ival(cfg%alias_max), "2 to 1024"); return
        end if
        if (all(cfg%fft_planner /= [character(len=16) :: 'estimate', 'measure', 'patient'])) then
            call fail("&solver fft_planner", "'"//trim(cfg%fft_planner)//"'", "'estimate', 'measure' or 'patient'")
            return
        end if
        if (cfg%anderson_memory < 0 .or. cfg%anderson_memory > 50) then
            call fail("&solver anderson_memory", ival(cfg%anderson_memory), "0 (off) to 50"); return
        end if
        if (cfg%balance_every < 1 .or. cfg%balance_every > 100000) then
            call fail("&solver balance_every", ival(cfg%balance_every), "1 to 100000"); return
        end if
        if (.not. (cfg%balance_ratio >= 1.0_dp .and. cfg%balance_ratio <= 1.0e6_dp)) then
            call fail("&solver balance_ratio", rval(cfg%balance_ratio), "1 to 1e6"); return
        end if
        if (.not. (cfg%balance_factor > 1.0_dp .and. cfg%balance_factor <= 100.0_dp)) then
            call fail("&solver balance_factor", rval(cfg%balance_factor), "> 1 and <= 100"); return
        end if
        if (cfg%threads < 1 .or. cfg%threads > 1024) then
            call fail("&solver threads", ival(cfg%threads), "1 to 1024"); return
        end if
        if (cfg%zeta2 == 0.0_dp) cfg%zeta2 = max(cfg%k_cut, cfg%zeta1)
        if (.not. (cfg%zeta1 >= 0.0_dp .and. cfg%zeta1 < cfg%zeta2 .and. cfg%zeta2 < 1.0e6_dp)) then
            call fail("&analysis zeta1/zeta2", rval(cfg%zeta1)//"/"//rval(cfg%zeta2), &
                "0 <= zeta1 < zeta2 (band in multiples of 2 pi/lx_m; zeta2 = 0 means k_cut)"); return
        end if
        if (cfg%n_theta < 4 .or. cfg%n_theta > 100000) then
            call fail("&analysis n_theta", ival(cfg%n_theta), "4 to 100000"); return
        end if
        if (.not. (cfg%iso_tol >= 0.0_dp .and. cfg%iso_tol < 1.0_dp)) then
            call fail("&analysis iso_tol", rval(cfg%iso_tol), "0 <= iso_tol < 1"); return
        end if
        if (any(.not. (cfg%sweep_speeds >= 0.0_dp .and. cfg%sweep_speeds < big))) then
            call fail("&sweep speeds_m_s", "", "every speed >= 0 [m/s]"); return
        end if
        if (any(.not. (abs(cfg%sweep_alphas) <= 360.0_dp))) then
            call fail("&sweep alphas_deg", "", "every angle -360 to 360 [degrees]"); return
        end if
        if (any(.not. (cfg%sweep_eccs > 0.0_dp .and. cfg%sweep_eccs <= 1.0_dp))) then
            call fail("&sweep eccentricities", "", "every value 0 < eccentricity <= 1"); return
        end if
        if (any(.not. (cfg%sweep_pressures > 0.0_dp .and. cfg%sweep_pressures < big))) then
            call fail("&sweep pressures_pa", "", "every pressure > 0 [Pa]"); return
        end if
        if ((size(cfg%sweep_alphas) > 0 .or. size(cfg%sweep_eccs) > 0) .and. cfg%surface_kind /= 'self_affine') then
            call fail("&sweep alphas_deg/eccentricities", "", "only with &surface kind = 'self_affine'"); return
        end if
        if (len(cfg%output_file) == 0) then
            call fail("&output file", "''", "a file path"); return
        end if

    contains

        subroutine fail(what, value, allowed)
            character(len=*), intent(in) :: what, value, allowed
            call fatal_error(error, at//what//" = "//value//" is out of range (allowed: "//allowed//")")
        end subroutine fail

    end subroutine check_config

    !> Fill unset cell lengths: lx from `lx_default`, ly from lx*ny/nx (square cells)
    subroutine default_lengths(cfg, lx_default)
        type(config_t), intent(inout) :: cfg
        real(dp), intent(in) :: lx_default
        if (cfg%lx_m == 0.0_dp) cfg%lx_m = lx_default
        if (cfg%ly_m == 0.0_dp) cfg%ly_m = cfg%lx_m*cfg%ny/cfg%nx
    end subroutine default_lengths

    !> Is the wave of (wavelength, direction) periodic on the cell and below Nyquist?
    logical function periodic_wave(cfg) result(ok)
        type(config_t), intent(in) :: cfg
        real(dp) :: kx, ky, th
        th = cfg%direction_deg*acos(-1.0_dp)/180.0_dp
        kx = cfg%lx_m*cos(th)/cfg%wavelength_m
        ky = cfg%ly_m*sin(th)/cfg%wavelength_m
        if (cfg%surface_kind == 'bisinusoid') then
            kx = cfg%lx_m/cfg%wavelength_m; ky = cfg%ly_m/cfg%wavelength_m
        end if
        ok = abs(kx - anint(kx)) < 1.0e-9_dp*max(1.0_dp, abs(kx)) .and. &
             abs(ky - anint(ky)) < 1.0e-9_dp*max(1.0_dp, abs(ky)) .and. &
             abs(kx) < 0.5_dp*cfg%nx .and. abs(ky) < max(0.5_dp*cfg%ny, 0.5_dp)
    end function periodic_wave

    function ival(i) result(s)
        integer, intent(in) :: i
        character(len=:), allocatable :: s
        character(len=24) :: buf
        write (buf, '(i0)') i
        s = trim(buf)
    end function ival

    function rval(x) result(s)
        real(dp), intent(in) :: x
        character(len=:), allocatable :: s
        character(len=32) :: buf
        write (buf, '(g0.6)') x
        s = trim(adjustl(buf))
    end function rval

end module veslide_config
