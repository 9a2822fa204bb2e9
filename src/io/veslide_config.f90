!> The namelist input: one file, groups &grid, &surface, &material, &load, &motion, &interface,
!> &solver, &analysis, &sweep, &output, each read and checked by its own module (veslide_config_<group>),
!> composed here into `config_t`, with the checks that involve several groups.
!>
!> Every group is optional (defaults apply); every value is range-checked, and a failure is an
!> `error_t` whose message names the file, the group, the variable and the allowed range.
module veslide_config
    use veslide_kinds, only: dp, radians
    use veslide_error, only: error_t, fatal_error, add_context
    use veslide_strings, only: str, sig
    use veslide_warning, only: warning_t, add_warning
    use veslide_system, only: missing_reason
    use veslide_config_common, only: require, group_text_t, scan_namelist, get_group
    use veslide_config_grid, only: grid_config_t, read_grid_config
    use veslide_config_surface, only: surface_config_t, read_surface_config
    use veslide_config_material, only: material_config_t, read_material_config, max_time
    use veslide_config_load, only: load_config_t, read_load_config
    use veslide_config_adhesion, only: adhesion_config_t, read_adhesion_config
    use veslide_config_motion, only: motion_config_t, read_motion_config
    use veslide_config_interface, only: interface_config_t, read_interface_config
    use veslide_config_solver, only: solver_config_t, read_solver_config
    use veslide_config_analysis, only: analysis_config_t, read_analysis_config
    use veslide_config_sweep, only: sweep_config_t, read_sweep_config
    use veslide_config_output, only: output_config_t, read_output_config
    use veslide_topography, only: topography_info_t, topography_info
    use veslide_material, only: shift_factor, coupling_beta
    use veslide_validity, only: edge_jumps, edge_jump_limit
    use veslide_contact_law, only: contact_law_t, new_adhesive_law, law_id
    use veslide_solver_options, only: solver_method_id
    use veslide_solver_table, only: operator_symmetric, motion_on_grid, shear_symmetric, method_refusal
    implicit none
    private
    public :: config_t, warning_t, read_config, read_text_file, default_config, complete_config, case_law, &
              case_speeds, case_symmetric

    !> The groups of a namelist file, in the order of the README
    character(len=*), parameter :: group_names(11) = [character(len=9) :: 'grid', 'surface', 'material', 'load', &
                                                      'adhesion', 'motion', 'interface', 'solver', 'analysis', &
                                                      'sweep', 'output']

    type :: config_t
        character(len=:), allocatable :: path        !! namelist file
        character(len=:), allocatable :: text        !! its text, verbatim
        !> what the input asks that changes nothing, or that its files say of themselves (source
        !> 'input'; veslide_warning)
        type(warning_t), allocatable :: warnings(:)
        type(grid_config_t) :: grid
        type(surface_config_t) :: surface
        type(material_config_t) :: material
        type(load_config_t) :: load
        type(adhesion_config_t) :: adhesion
        type(motion_config_t) :: motion
        type(interface_config_t) :: interface
        type(solver_config_t) :: solver
        type(analysis_config_t) :: analysis
        type(sweep_config_t) :: sweep
        type(output_config_t) :: output
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
            call fatal_error(error, "veslide: cannot open '"//path//"': "//missing_reason(path)); return
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
    subroutine read_config(path, cfg, error, surface_statistics)
        character(len=*), intent(in) :: path
        type(config_t), intent(out) :: cfg
        type(error_t), allocatable, intent(out) :: error
        !> read a height file whole for its edge statistics (warnings); .false. on the processes
        !> of a distributed run that do not print (default .true.)
        logical, intent(in), optional :: surface_statistics
        type(group_text_t), allocatable :: groups(:)

        cfg%path = path
        call read_text_file(path, cfg%text, error); if (allocated(error)) return
        call scan_namelist(path, cfg%text, group_names, groups, error); if (allocated(error)) return
        call read_grid_config(cfg%grid, get_group(groups, 'grid'), path, error); if (allocated(error)) return
        call read_surface_config(cfg%surface, get_group(groups, 'surface'), path, error); if (allocated(error)) return
        call read_material_config(cfg%material, get_group(groups, 'material'), path, error)
        if (allocated(error)) return
        call read_adhesion_config(cfg%adhesion, get_group(groups, 'adhesion'), path, error)
        if (allocated(error)) return
        call read_load_config(cfg%load, get_group(groups, 'load'), path, error, adhesive=cfg%adhesion%law /= 'none')
        if (allocated(error)) return
        call read_motion_config(cfg%motion, get_group(groups, 'motion'), path, error); if (allocated(error)) return
        call read_interface_config(cfg%interface, get_group(groups, 'interface'), path, error)
        if (allocated(error)) return
        call read_solver_config(cfg%solver, get_group(groups, 'solver'), path, error); if (allocated(error)) return
        call read_analysis_config(cfg%analysis, get_group(groups, 'analysis'), path, error)
        if (allocated(error)) return
        call read_sweep_config(cfg%sweep, get_group(groups, 'sweep'), path, error, adhesive=cfg%adhesion%law /= 'none')
        if (allocated(error)) return
        call read_output_config(cfg%output, get_group(groups, 'output'), path, error); if (allocated(error)) return
        call complete_config(cfg, error, surface_statistics)
    end subroutine read_config

    !> Every default, for programs that build cases in code (benchmarks, scenes, tests): set what
    !> differs, then call complete_config, which fills the defaults that depend on other groups
    !> and checks across groups, as read_config does
    subroutine default_config(cfg, path)
        type(config_t), intent(out) :: cfg
        character(len=*), intent(in) :: path
        cfg%path = path; cfg%text = ''
        cfg%surface%kind = 'self_affine'; cfg%surface%scale_to = 'realised'
        cfg%surface%file = ''; cfg%surface%dataset = '/height_m'; cfg%surface%preparation = ''
        cfg%material%model = 'elastic'; cfg%material%shift = 'none'; cfg%material%base = 'bonded'
        allocate (cfg%material%prony_coef(0), cfg%material%prony_time_s(0))
        allocate (cfg%material%shift_table_c(0), cfg%material%shift_table_log10(0))
        cfg%solver%method = 'auto'; cfg%solver%kernel = 'spectral'; cfg%solver%fft_planner = 'measure'
        cfg%solver%device = 'auto'
        allocate (cfg%sweep%speeds(0), cfg%sweep%alphas(0), cfg%sweep%eccentricities(0), cfg%sweep%pressures(0), &
                  cfg%sweep%temperatures(0), cfg%sweep%approaches(0))
        allocate (cfg%sweep%seeds(0))
        cfg%output%file = 'veslide.h5'
        cfg%adhesion%law = 'none'
        allocate (cfg%warnings(0))
        allocate (character(len=32) :: cfg%surface%given(0), cfg%material%given(0))   ! (nothing read)
    end subroutine default_config

    !> Defaults that depend on other groups, and the checks across groups
    subroutine complete_config(cfg, error, surface_statistics)
        type(config_t), intent(inout) :: cfg
        type(error_t), allocatable, intent(out) :: error
        logical, intent(in), optional :: surface_statistics
        character(len=:), allocatable :: p
        real(dp) :: nyq
        integer :: k
        p = cfg%path
        cfg%surface%preparation = ''
        if (cfg%surface%kind /= 'file') then
            call default_lengths(cfg, 0.01_dp)
        else
            call file_grid(cfg, error, surface_statistics); if (allocated(error)) return
        end if
        select case (cfg%surface%kind)
        case ('self_affine')
            nyq = 0.5_dp*min(real(cfg%grid%nx, dp), cfg%grid%ny*cfg%grid%lx_m/cfg%grid%ly_m)
            if (cfg%surface%k_cut_given) then
                call require(error, cfg%surface%k_cut < nyq, p, 'surface', 'k_cut', str(cfg%surface%k_cut), &
                             ">= k_roll and below the Nyquist wavenumber "//str(nyq)//" of the grid")
            else if (.not. cfg%surface%k_cut < nyq) then
                ! the default 64 on a grid too small for it: half the grid's Nyquist (four cells
                ! per shortest wavelength, the scan preparation's default)
                cfg%surface%k_cut = max(0.5_dp*nyq, cfg%surface%k_roll)
                call require(error, cfg%surface%k_cut < nyq, p, 'surface', 'k_roll', str(cfg%surface%k_roll), &
                             "below the Nyquist wavenumber "//str(nyq)//" of the grid (k_cut defaults to half of it)")
            end if
        case ('cosine', 'bisinusoid')
            call require(error, periodic_wave(cfg), p, 'surface', 'wavelength_m/direction_deg', &
                         str(cfg%surface%wavelength_m)//"/"//str(cfg%surface%direction_deg), &
                         "a wave periodic on the cell: lx_m*cos(direction)/wavelength_m and "// &
                         "ly_m*sin(direction)/wavelength_m whole numbers below nx/2, ny/2")
        end select
        if (allocated(error)) return
        call check_interface(cfg, error); if (allocated(error)) return
        call check_method(cfg, error); if (allocated(error)) return
        if (cfg%load%approach_m /= huge(1.0_dp) .and. size(cfg%sweep%pressures) > 0) then
            call fatal_error(error, "veslide: "//p//": &load approach_m (approach control) with &sweep pressures_pa:"// &
                             " give the loads or the approach, not both"); return
        end if
        if (cfg%load%approach_m /= huge(1.0_dp) .and. size(cfg%sweep%approaches) > 0) then
            call fatal_error(error, "veslide: "//p//": &load approach_m with &sweep approaches_m: give the"// &
                             " approaches in one place (the &sweep list replaces &load)"); return
        end if
        if (cfg%analysis%zeta2 == 0.0_dp) cfg%analysis%zeta2 = max(cfg%surface%k_cut, cfg%analysis%zeta1)
        call require(error, cfg%analysis%zeta1 >= 0.0_dp .and. cfg%analysis%zeta1 < cfg%analysis%zeta2 .and. &
                     cfg%analysis%zeta2 < 1.0e6_dp, p, 'analysis', 'zeta1/zeta2', &
                     str(cfg%analysis%zeta1)//"/"//str(cfg%analysis%zeta2), &
                     "0 <= zeta1 < zeta2 (band in multiples of 2 pi/lx_m; zeta2 = 0 means k_cut)")
        call require(error, (size(cfg%sweep%alphas) == 0 .and. size(cfg%sweep%eccentricities) == 0) .or. &
                     cfg%surface%kind == 'self_affine', p, 'sweep', 'alphas_deg/eccentricities', &
                     list_text(cfg%sweep%alphas)//"/"//list_text(cfg%sweep%eccentricities), &
                     "only with &surface kind = 'self_affine' (here '"//cfg%surface%kind//"')")
        call require(error, size(cfg%sweep%temperatures) == 0 .or. cfg%material%shift /= 'none', p, 'sweep', &
                     'temperatures_c', list_text(cfg%sweep%temperatures), &
                     "only with a &material shift ('wlf', 'arrhenius' or 'table') and its reference")
        if (allocated(error)) return
        call check_shift(cfg%material%temperature_c, 'material', 'temperature_c')
        do k = 1, size(cfg%sweep%temperatures)
            call check_shift(cfg%sweep%temperatures(k), 'sweep', 'temperatures_c('//str(k)//')')
        end do
        if (allocated(error)) return
        if (cfg%material%shift == 'wlf') then
            do k = 1, size(cfg%sweep%temperatures)
                call require(error, cfg%sweep%temperatures(k) - cfg%material%reference_temperature_c > &
                             -cfg%material%wlf_c2_k, p, 'sweep', 'temperatures_c('//str(k)//')', &
                             str(cfg%sweep%temperatures(k)), "above reference_temperature_c - wlf_c2_k = "// &
                             str(cfg%material%reference_temperature_c - cfg%material%wlf_c2_k))
            end do
            if (allocated(error)) return
        end if
        call check_pressure_against_moduli(cfg, error); if (allocated(error)) return
        if (cfg%sweep%n_seeds > 0) cfg%sweep%seeds = [(cfg%surface%seed + k, k = 0, cfg%sweep%n_seeds - 1)]
        if (cfg%sweep%is_study() .and. .not. cfg%output%fields_given) cfg%output%fields = .false.
        call collect_warnings(cfg)
    contains
        subroutine check_shift(t_c, group, var)
            real(dp), intent(in) :: t_c
            character(len=*), intent(in) :: group, var
            call check_shift_range(cfg, t_c, group, var, error)
        end subroutine check_shift
    end subroutine complete_config

    !> &solver method against what every case of the input asks of it (its operator, symmetric or
    !> not at each of its speeds on its grid; its contact law): the solver table's refusal
    !> (veslide_solver_table), in the words the solve would use. Where the device runs the method
    !> is checked before a case is built (veslide_memory), after the command line's --device.
    subroutine check_method(cfg, error)
        type(config_t), intent(in) :: cfg
        type(error_t), allocatable, intent(out) :: error
        type(contact_law_t) :: law
        character(len=:), allocatable :: why
        law = case_law(cfg)
        why = method_refusal(solver_method_id(cfg%solver%method), case_symmetric(cfg), law%kind)
        if (len(why) > 0) call fatal_error(error, "veslide: "//cfg%path//": "//why)
    end subroutine check_method

    !> Is the operator of every case of the input symmetric (veslide_solver_table): its solid's
    !> (elastic, or at rest at every speed) on a grid the motion reaches, and its interfacial
    !> shear's (none, an incompressible solid, or a grid the shear's direction does not reach)
    pure logical function case_symmetric(cfg) result(yes)
        type(config_t), intent(in) :: cfg
        yes = (operator_symmetric(cfg%material%model == 'elastic', case_speeds(cfg)) .or. &
               .not. motion_on_grid(cfg%grid%nx, cfg%grid%ny, case_speeds(cfg), cfg%motion%direction_deg)) .and. &
              shear_symmetric(coupling_beta(cfg%material%poisson)*cfg%interface%shear_coefficient, cfg%grid%nx, &
                              cfg%grid%ny, cfg%motion%direction_deg)
    end function case_symmetric

    !> &interface against the solid: an interfacial shear on a layer is refused (the coupling
    !> derived for it, beta, is the half-space's; a layer on a rigid base couples the normal and
    !> tangential displacements by another function of q d, not zero even at poisson = 0.5)
    subroutine check_interface(cfg, error)
        type(config_t), intent(in) :: cfg
        type(error_t), allocatable, intent(out) :: error
        if (cfg%interface%shear_coefficient > 0.0_dp .and. cfg%material%thickness_m > 0.0_dp) &
            call fatal_error(error, "veslide: "//cfg%path//": &interface shear_coefficient = "// &
                sig(cfg%interface%shear_coefficient)//" with &material thickness_m = "//sig(cfg%material%thickness_m)// &
                ": an interfacial shear on a layer is not available (the coupling of its normal and tangential"// &
                " displacements is another function of q d and the base, not zero even at poisson = 0.5, and is"// &
                " not derived here; docs/interface.md): remove one of the two")
    end subroutine check_interface

    !> The speeds the cases of the input slide at [m/s]: &sweep's, or the one of &motion
    pure function case_speeds(cfg) result(speeds)
        type(config_t), intent(in) :: cfg
        real(dp), allocatable :: speeds(:)
        if (size(cfg%sweep%speeds) > 0) then
            speeds = cfg%sweep%speeds
        else
            speeds = [cfg%motion%speed_m_s]
        end if
    end function case_speeds

    !> The contact law the input asks for: the hard wall, or &adhesion's law (veslide_case_spec
    !> and the check of &solver method read it from here)
    pure function case_law(cfg) result(law)
        type(config_t), intent(in) :: cfg
        type(contact_law_t) :: law
        law = contact_law_t()
        if (cfg%adhesion%law /= 'none') law = new_adhesive_law(law_id(cfg%adhesion%law), cfg%adhesion%energy_j_m2, &
                                                              cfg%adhesion%range_m)
    end function case_law

    !> The temperature `t_c` within a shift table (measured shift factors are not extrapolated),
    !> and the shifted times there within the range the input accepts for a time (1e-300 to
    !> 1e200 s; a_T overflows near WLF's divergence and near 0 K)
    subroutine check_shift_range(cfg, t_c, group, var, error)
        type(config_t), intent(in) :: cfg
        real(dp), intent(in) :: t_c
        character(len=*), intent(in) :: group, var
        type(error_t), allocatable, intent(inout) :: error
        real(dp) :: a, lo, hi
        integer :: n
        if (allocated(error) .or. cfg%material%shift == 'none') return
        associate (m => cfg%material)
            if (m%shift == 'wlf') then
                if (.not. t_c - m%reference_temperature_c > -m%wlf_c2_k) return   ! refused with its own message
            end if
            if (m%shift == 'table') then
                n = size(m%shift_table_c)
                call require(error, t_c >= m%shift_table_c(1) .and. t_c <= m%shift_table_c(n), cfg%path, group, var, &
                             str(t_c), "within the &material shift table, shift_temperatures_c = "// &
                             str(m%shift_table_c(1))//" to "//str(m%shift_table_c(n))// &
                             " [C]: measured shift factors are not extrapolated")
                if (allocated(error)) return
            end if
            a = shift_factor(m%shift, t_c, m%reference_temperature_c, m%wlf_c1, m%wlf_c2_k, m%activation_energy_j_mol, &
                             m%shift_table_c, m%shift_table_log10)
            select case (m%model)
            case ('one_term')
                lo = m%tau_s; hi = m%tau_s
            case ('creep', 'relaxation')
                lo = minval(m%prony_time_s); hi = maxval(m%prony_time_s)
            case default
                return
            end select
            if (.not. (a*hi <= max_time .and. a*lo >= 1.0e-300_dp)) call fatal_error(error, "veslide: "//cfg%path// &
                ": &"//group//" "//var//" = "//str(t_c)//" shifts the material's times by a_T = "//str(a)// &
                " beyond 1e-300 to 1e200 s (closer to where the "//m%shift//" law diverges than the material allows)")
        end associate
    end subroutine check_shift_range

    !> A height file fixes the grid: its points, and its sides from its attributes; &grid may
    !> repeat them but not contradict them (a file is never resampled silently: the Python
    !> package's `veslide.topography` resamples). A file whose opposite edges jump gets a warning.
    subroutine file_grid(cfg, error, statistics)
        type(config_t), intent(inout) :: cfg
        type(error_t), allocatable, intent(out) :: error
        logical, intent(in), optional :: statistics
        type(topography_info_t) :: info
        character(len=:), allocatable :: p, what
        real(dp), parameter :: same = 1.0e-9_dp
        p = cfg%path
        call topography_info(cfg%surface%file, cfg%surface%dataset, info, error, statistics)
        call add_context(error, "veslide: "//p//": &surface ")
        if (allocated(error)) return
        what = " disagrees with the height file '"//cfg%surface%file//"' ("//str(info%nx)//" x "//str(info%ny)// &
               " points"
        if (info%lx_m > 0.0_dp) what = what//", "//str(info%lx_m)//" m x "//str(info%ly_m)//" m"
        what = what//"): leave it out, or resample the file (python -m veslide topography FILE --nx N --ny N)"
        if (cfg%grid%nx_given .and. cfg%grid%nx /= info%nx) then
            call fatal_error(error, "veslide: "//p//": &grid nx = "//str(cfg%grid%nx)//what); return
        end if
        if (cfg%grid%ny_given .and. cfg%grid%ny /= info%ny) then
            call fatal_error(error, "veslide: "//p//": &grid ny = "//str(cfg%grid%ny)//what); return
        end if
        cfg%grid%nx = info%nx; cfg%grid%ny = info%ny
        if (cfg%grid%lx_m > 0.0_dp .and. info%lx_m > 0.0_dp) then
            if (abs(cfg%grid%lx_m - info%lx_m) > same*info%lx_m) then
                call fatal_error(error, "veslide: "//p//": &grid lx_m = "//str(cfg%grid%lx_m)//what); return
            end if
        end if
        if (cfg%grid%ly_m > 0.0_dp .and. info%ly_m > 0.0_dp) then
            if (abs(cfg%grid%ly_m - info%ly_m) > same*info%ly_m) then
                call fatal_error(error, "veslide: "//p//": &grid ly_m = "//str(cfg%grid%ly_m)//what); return
            end if
        end if
        if (cfg%grid%lx_m == 0.0_dp) cfg%grid%lx_m = info%lx_m
        if (cfg%grid%ly_m == 0.0_dp) cfg%grid%ly_m = info%ly_m
        ! only the side along y known (&grid ly_m, or the attribute length_y_m): square cells
        if (cfg%grid%lx_m == 0.0_dp .and. cfg%grid%ly_m > 0.0_dp) cfg%grid%lx_m = cfg%grid%ly_m*cfg%grid%nx/cfg%grid%ny
        if (cfg%grid%lx_m == 0.0_dp) then
            call fatal_error(error, "veslide: "//p//": &surface file '"//cfg%surface%file//"': the cell side is"// &
                " unknown: set &grid lx_m or the dataset's attribute length_x_m"); return
        end if
        if (cfg%grid%ly_m == 0.0_dp) cfg%grid%ly_m = cfg%grid%lx_m*cfg%grid%ny/cfg%grid%nx
        cfg%surface%preparation = info%preparation
        cfg%surface%edge_jump = [info%jump_x, info%jump_y]
        cfg%surface%edge_step = [info%step_x, info%step_y]
        cfg%surface%filled_fraction = info%filled_fraction
        cfg%surface%band_slope_removed = info%band_slope_removed
    end subroutine file_grid

    !> Inputs that run but change nothing, and what the input's files say of themselves (a height
    !> file's edges), one warning each (veslide_warning; codes in docs/validity.md)
    subroutine collect_warnings(cfg)
        type(config_t), intent(inout) :: cfg
        if (allocated(cfg%warnings)) deallocate (cfg%warnings)
        allocate (cfg%warnings(0))
        if (size(cfg%sweep%speeds) > 1 .and. cfg%material%model == 'elastic') then
            if (cfg%interface%shear_coefficient > 0.0_dp) then
                call warn('elastic-speeds', "&sweep speeds on an elastic &material: the solution and the friction"// &
                          " (the interfacial shear's, which does not depend on the speed) are the same at every speed")
            else
                call warn('elastic-speeds', "&sweep speeds on an elastic &material: the solution and the zero"// &
                          " friction are the same at every speed")
            end if
        end if
        if (size(cfg%sweep%speeds) == 0 .and. cfg%motion%speed_m_s > 0.0_dp .and. cfg%material%model == 'elastic') then
            if (cfg%interface%shear_coefficient > 0.0_dp) then
                call warn('elastic-speeds', "&motion speed_m_s on an elastic &material: the solution and the"// &
                          " friction (the interfacial shear's) do not depend on the speed; its direction alone"// &
                          " sets the shear's")
            else
                call warn('elastic-speeds', "&motion speed_m_s on an elastic &material: the solution does not"// &
                          " depend on the speed and the friction is zero (a viscoelastic &material model slides"// &
                          " with friction)")
            end if
        end if
        if (size(cfg%sweep%alphas) > 1 .and. size(cfg%sweep%eccentricities) == 0 .and. &
            cfg%surface%eccentricity == 1.0_dp) &
            call warn('isotropic-angles', "&sweep alphas_deg with &surface eccentricity = 1: the spectrum is"// &
                      " isotropic, every angle gives the same surface")
        if ((size(cfg%sweep%seeds) > 1 .or. cfg%sweep%n_seeds > 1) .and. cfg%surface%kind /= 'self_affine') &
            call warn('unused-input', "&sweep seeds with &surface kind = '"//cfg%surface%kind//"': only a"// &
                      " random surface depends on its seed, every case repeats the first")
        if (cfg%material%shift /= 'none' .and. cfg%material%model == 'elastic') &
            call warn('elastic-shift', "&material shift = '"//cfg%material%shift//"' on an elastic &material:"// &
                      " an elastic solid has no times to shift, every temperature gives the same solution")
        if (size(cfg%sweep%speeds) > 0 .and. cfg%motion%speed_m_s /= 0.0_dp) &
            call warn('replaced-input', "&motion speed_m_s = "//str(cfg%motion%speed_m_s)//" is replaced by the"// &
                      " &sweep speeds")
        if (size(cfg%sweep%temperatures) > 0 .and. cfg%material%temperature_c /= cfg%material%reference_temperature_c) &
            call warn('replaced-input', "&material temperature_c = "//str(cfg%material%temperature_c)// &
                      " is replaced by the &sweep temperatures_c")
        if (cfg%material%thickness_m == 0.0_dp .and. cfg%material%base /= 'bonded') &
            call warn('unused-input', "&material base = '"//cfg%material%base//"' without a thickness_m: the"// &
                      " solid is a half-space")
        if (.not. allocated(cfg%surface%given)) allocate (character(len=32) :: cfg%surface%given(0))
        if (.not. allocated(cfg%material%given)) allocate (character(len=32) :: cfg%material%given(0))
        if (cfg%surface%kind == 'file') then
            call unused('surface', cfg%surface%given, surface_reads(), "kind = 'file' (the heights are the file's)")
        else
            call unused('surface', cfg%surface%given, surface_reads(), "kind = '"//cfg%surface%kind//"'")
        end if
        call unused('material', cfg%material%given, material_reads(), "model = '"//cfg%material%model//"'")
        if (cfg%surface%kind == 'file') then
            if (edge_jumps(cfg%surface%edge_jump(1), cfg%surface%edge_step(1))) call warn('edge-jump', &
                edge_text('x', 'rows', 1), cfg%surface%edge_jump(1), edge_jump_limit)
            if (edge_jumps(cfg%surface%edge_jump(2), cfg%surface%edge_step(2))) call warn('edge-jump', &
                edge_text('y', 'columns', 2), cfg%surface%edge_jump(2), edge_jump_limit)
        end if
    contains
        function edge_text(axis, lines, k) result(t)
            character(len=*), intent(in) :: axis, lines
            integer, intent(in) :: k
            character(len=:), allocatable :: t
            character(len=16) :: a, b
            write (a, '(f0.2)') cfg%surface%edge_jump(k); write (b, '(f0.2)') cfg%surface%edge_step(k)
            if (a(1:1) == '.') a = '0'//a
            if (b(1:1) == '.') b = '0'//b
            t = "the heights of '"//cfg%surface%file//"' jump by "//trim(a)//" h_rms across its edges along "// &
                axis//" (rms over the "//lines//"; neighbours inside differ by "//trim(b)//" h_rms): it is solved"// &
                " as periodic, so its images step there; make it periodic first (python -m veslide topography"// &
                " FILE --periodic tukey)"
        end function edge_text

        !> The &surface variables its kind reads (kind itself aside)
        function surface_reads() result(names)
            character(len=16), allocatable :: names(:)
            select case (cfg%surface%kind)
            case ('self_affine')
                names = [character(len=16) :: 'seed', 'hurst', 'eccentricity', 'alpha_deg', 'k_low', 'k_roll', &
                         'k_cut', 'rms_slope', 'rms_height_m', 'scale_to']
            case ('cosine')
                names = [character(len=16) :: 'amplitude_m', 'wavelength_m', 'direction_deg']
            case ('bisinusoid')
                names = [character(len=16) :: 'amplitude_m', 'wavelength_m']
            case ('paraboloid', 'cylinder')
                names = [character(len=16) :: 'radius_m']
            case ('file')
                names = [character(len=16) :: 'file', 'dataset']
            case default
                allocate (names(0))
            end select
            ! k_cut is the default upper end of the anisotropy band (&analysis zeta2) of any surface
            if (cfg%surface%kind /= 'self_affine') names = [character(len=16) :: names, 'k_cut']
            names = [character(len=16) :: names, 'kind']
        end function surface_reads

        !> The &material variables its model reads (with the shift's and the layer's, which the
        !> material's own checks guard)
        function material_reads() result(names)
            character(len=24), allocatable :: names(:)
            select case (cfg%material%model)
            case ('elastic')
                names = [character(len=24) :: 'young_pa']
            case ('one_term')
                names = [character(len=24) :: 'einf_pa', 'ratio', 'tau_s']
            case ('creep')
                names = [character(len=24) :: 'e0_pa', 'creep_c_per_pa', 'creep_tau_s']
            case default
                names = [character(len=24) :: 'e0_pa', 'relax_e_pa', 'relax_rho_s']
            end select
            names = [character(len=24) :: names, 'model', 'poisson', 'shift', 'temperature_c', &
                     'reference_temperature_c', 'wlf_c1', 'wlf_c2_k', 'activation_energy_j_mol', 'thickness_m', 'base', &
                     'shift_temperatures_c', 'shift_log10_at']
        end function material_reads

        !> One warning naming the variables of `group` the input gave and `what` does not read
        subroutine unused(group, given, reads, what)
            character(len=*), intent(in) :: group, given(:), reads(:), what
            character(len=:), allocatable :: list
            integer :: k, n
            if (size(given) == 0) return
            list = ''; n = 0
            do k = 1, size(given)
                if (any(reads == given(k))) cycle
                if (n > 0) list = list//", "
                list = list//trim(given(k)); n = n + 1
            end do
            if (n == 0) return
            if (n == 1) then
                call warn('unused-input', "&"//group//" "//list//" is not used with "//what//": it changes"// &
                          " nothing (remove it)")
            else
                call warn('unused-input', "&"//group//" "//list//" are not used with "//what//": they change"// &
                          " nothing (remove them)")
            end if
        end subroutine unused

        subroutine warn(code, text, value, threshold)
            character(len=*), intent(in) :: code, text
            real(dp), intent(in), optional :: value, threshold
            call add_warning(cfg%warnings, code, text, 'input', value, threshold)
        end subroutine warn
    end subroutine collect_warnings

    !> A nominal pressure above the solid's glassy contact modulus Einf/(1 - nu^2) would strain
    !> it by more than 1 wherever it touched, in any state: no linear (visco)elastic model holds,
    !> and the likely cause is a modulus in kPa or MPa read as Pa (or a pressure in the wrong unit)
    subroutine check_pressure_against_moduli(cfg, error)
        type(config_t), intent(in) :: cfg
        type(error_t), allocatable, intent(inout) :: error
        real(dp) :: e0, einf, p, estar
        if (allocated(error)) return
        call material_moduli(cfg, e0, einf)
        estar = einf/(1.0_dp - cfg%material%poisson**2)
        p = cfg%load%mean_pressure_pa
        if (size(cfg%sweep%pressures) > 0) p = maxval(cfg%sweep%pressures)     ! (they replace &load's)
        if (.not. p > estar) return
        if (size(cfg%sweep%pressures) > 0) then
            call fatal_error(error, "veslide: "//cfg%path//": &sweep pressures_pa up to "//sig(p)//" Pa exceed"// &
                " the solid's largest contact modulus Einf/(1 - nu^2) = "//sig(estar)//" Pa (&material): the solid"// &
                " would be strained beyond 1 wherever it touched; moduli in kPa or MPa read as Pa?")
        else
            call fatal_error(error, "veslide: "//cfg%path//": &load mean_pressure_pa = "//sig(p)//" Pa exceeds"// &
                " the solid's largest contact modulus Einf/(1 - nu^2) = "//sig(estar)//" Pa (&material): the solid"// &
                " would be strained beyond 1 wherever it touched; moduli in kPa or MPa read as Pa?")
        end if
    end subroutine check_pressure_against_moduli

    !> The relaxed (w -> 0) and glassy (w -> infinity) Young's moduli of &material [Pa]
    pure subroutine material_moduli(cfg, e0, einf)
        type(config_t), intent(in) :: cfg
        real(dp), intent(out) :: e0, einf
        associate (m => cfg%material)
            select case (m%model)
            case ('one_term')
                einf = m%einf_pa; e0 = m%einf_pa/m%ratio
            case ('creep')
                e0 = m%e0_pa; einf = 1.0_dp/(1.0_dp/m%e0_pa - sum(m%prony_coef))
            case ('relaxation')
                e0 = m%e0_pa; einf = m%e0_pa + sum(m%prony_coef)
            case default
                e0 = m%young_pa; einf = m%young_pa
            end select
        end associate
    end subroutine material_moduli

    !> A list of numbers as the input writes it: 'a, b, c'
    pure function list_text(x) result(t)
        real(dp), intent(in) :: x(:)
        character(len=:), allocatable :: t
        integer :: k
        t = ''
        do k = 1, size(x)
            if (k > 1) t = t//", "
            t = t//str(x(k))
        end do
    end function list_text

    !> Fill unset cell lengths: lx from `lx_default`, ly from lx*ny/nx (square cells)
    subroutine default_lengths(cfg, lx_default)
        type(config_t), intent(inout) :: cfg
        real(dp), intent(in) :: lx_default
        if (cfg%grid%lx_m == 0.0_dp) cfg%grid%lx_m = lx_default
        if (cfg%grid%ly_m == 0.0_dp) cfg%grid%ly_m = cfg%grid%lx_m*cfg%grid%ny/cfg%grid%nx
    end subroutine default_lengths

    !> Is the wave of (wavelength, direction) periodic on the cell and below Nyquist?
    pure logical function periodic_wave(cfg) result(ok)
        type(config_t), intent(in) :: cfg
        real(dp) :: kx, ky, th
        th = radians(cfg%surface%direction_deg)
        kx = cfg%grid%lx_m*cos(th)/cfg%surface%wavelength_m
        ky = cfg%grid%ly_m*sin(th)/cfg%surface%wavelength_m
        if (cfg%surface%kind == 'bisinusoid') then
            kx = cfg%grid%lx_m/cfg%surface%wavelength_m; ky = cfg%grid%ly_m/cfg%surface%wavelength_m
        end if
        ok = abs(kx - anint(kx)) < 1.0e-9_dp*max(1.0_dp, abs(kx)) .and. &
             abs(ky - anint(ky)) < 1.0e-9_dp*max(1.0_dp, abs(ky)) .and. &
             abs(kx) < 0.5_dp*cfg%grid%nx .and. abs(ky) < max(0.5_dp*cfg%grid%ny, 0.5_dp)
    end function periodic_wave


end module veslide_config
