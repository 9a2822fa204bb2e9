!> &surface: the rigid surface (random self-affine, a validation scene, or a measured file)
module veslide_config_surface
    use veslide_kinds, only: dp, i8
    use veslide_error, only: error_t
    use veslide_strings, only: str
    use veslide_config_common, only: group_text_t, diagnose_read, read_failed, split_lines, require, choices_text, is_one_of, &
                                     finite_in, check_text_length, max_text, unset_real, is_unset, &
                                     assigned_names
    use veslide_surface, only: surface_kind_names
    implicit none
    private
    public :: surface_config_t, read_surface_config

    type :: surface_config_t
        character(len=:), allocatable :: kind            !! one of surface_kind_names
        integer(i8) :: seed = 1_i8                       !! random seed
        real(dp) :: hurst = 0.8_dp                       !! Hurst exponent
        real(dp) :: eccentricity = 1.0_dp                !! PSD eccentricity b/a
        real(dp) :: alpha_deg = 0.0_dp                   !! major axis of the PSD from x [deg]
        real(dp) :: k_low = 1.0_dp, k_roll = 1.0_dp, k_cut = 64.0_dp   !! cut-offs [2 pi/lx_m]
        logical :: k_cut_given = .false.                 !! k_cut set in the input (not the default)
        real(dp) :: rms_slope = 0.025_dp                 !! target rms slope
        real(dp) :: rms_height_m = 0.0_dp                !! target rms height instead [m]
        character(len=:), allocatable :: scale_to        !! 'realised' or 'expected'
        real(dp) :: amplitude_m = 0.0_dp, wavelength_m = 0.0_dp, direction_deg = 0.0_dp, radius_m = 0.0_dp
        character(len=:), allocatable :: file            !! kind = 'file': HDF5 file of heights
        character(len=:), allocatable :: dataset         !! its dataset
        character(len=:), allocatable :: preparation     !! the file's record of its preparation ('')
        !> the file's edge jumps along x and y and the rms steps inside [h_rms] (veslide_topography)
        real(dp) :: edge_jump(2) = 0.0_dp, edge_step(2) = 0.0_dp
        !> the file's preparation: the share of the scan's points filled, the share of its slope
        !> variance the band removed (the height file's attributes; -1 when it does not say)
        real(dp) :: filled_fraction = -1.0_dp, band_slope_removed = -1.0_dp
        character(len=:), allocatable :: given(:)        !! the variables the input assigned
    end type surface_config_t

    character(len=*), parameter :: names(17) = [character(len=13) :: 'kind', 'seed', 'hurst', 'eccentricity', &
        'alpha_deg', 'k_low', 'k_roll', 'k_cut', 'rms_slope', 'rms_height_m', 'scale_to', 'amplitude_m', &
        'wavelength_m', 'direction_deg', 'radius_m', 'file', 'dataset']
    character(len=*), parameter :: kinds(17) = [character(len=32) :: "a quoted text ('self_affine')", &
        'an integer (64-bit)', 'a real number', 'a real number', 'a real number', 'a real number', 'a real number', &
        'a real number', 'a real number', 'a real number', "a quoted text ('realised')", 'a real number', &
        'a real number', 'a real number', 'a real number', "a quoted text (a file path)", "a quoted text ('/height_m')"]

contains

    !> Read &surface from its text (absent: defaults) and check what does not depend on the grid
    !> (the grid-dependent checks are the configuration's)
    subroutine read_surface_config(self, g, path, error)
        type(surface_config_t), intent(out) :: self
        type(group_text_t), intent(in) :: g
        character(len=*), intent(in) :: path
        type(error_t), allocatable, intent(out) :: error
        character(len=max_text + 1) :: kind
        character(len=max_text + 1) :: scale_to
        character(len=max_text + 1) :: file, dataset
        integer(i8) :: seed
        real(dp) :: hurst, eccentricity, alpha_deg, k_low, k_roll, k_cut, rms_slope, rms_height_m
        real(dp) :: amplitude_m, wavelength_m, direction_deg, radius_m, big
        integer :: stat
        character(len=512) :: msg
        character(len=:), allocatable :: lines(:)
        namelist /surface/ kind, seed, hurst, eccentricity, alpha_deg, k_low, k_roll, k_cut, rms_slope, &
            rms_height_m, scale_to, amplitude_m, wavelength_m, direction_deg, radius_m, file, dataset
        kind = 'self_affine'; seed = self%seed; hurst = self%hurst; eccentricity = self%eccentricity
        alpha_deg = self%alpha_deg; k_low = self%k_low; k_roll = self%k_roll; k_cut = unset_real()
        rms_slope = self%rms_slope; rms_height_m = self%rms_height_m; scale_to = 'realised'
        amplitude_m = self%amplitude_m; wavelength_m = self%wavelength_m; direction_deg = self%direction_deg
        radius_m = self%radius_m; file = ''; dataset = '/height_m'
        call split_lines(g%text, lines)
        read (lines, nml=surface, iostat=stat, iomsg=msg)
        if (read_failed(stat)) then
            call diagnose_read(stat, msg, path, 'surface', g%body, names, kinds, try, error); return
        end if
        call check_text_length(error, kind, path, 'surface', 'kind', g%body)
        call check_text_length(error, scale_to, path, 'surface', 'scale_to', g%body)
        call check_text_length(error, file, path, 'surface', 'file', g%body)
        call check_text_length(error, dataset, path, 'surface', 'dataset', g%body); if (allocated(error)) return
        self%kind = trim(kind); self%seed = seed; self%hurst = hurst; self%eccentricity = eccentricity
        self%alpha_deg = alpha_deg; self%k_low = k_low; self%k_roll = k_roll
        self%k_cut_given = .not. is_unset(k_cut)
        if (self%k_cut_given) self%k_cut = k_cut
        self%rms_slope = rms_slope; self%rms_height_m = rms_height_m; self%scale_to = trim(scale_to)
        self%amplitude_m = amplitude_m; self%wavelength_m = wavelength_m; self%direction_deg = direction_deg
        self%radius_m = radius_m; self%file = trim(file); self%dataset = trim(dataset)
        call assigned_names(g%body, self%given)

        big = 1.0e3_dp
        call require(error, is_one_of(self%kind, surface_kind_names), path, 'surface', 'kind', "'"//self%kind//"'", &
                     choices_text(surface_kind_names))
        if (allocated(error)) return
        select case (self%kind)
        case ('self_affine')
            call require(error, finite_in(hurst, 0.0_dp, 1.0_dp, open_low=.true.) .and. hurst < 1.0_dp, path, &
                         'surface', 'hurst', str(hurst), "0 < hurst < 1")
            call require(error, finite_in(eccentricity, 0.0_dp, 1.0_dp, open_low=.true.), path, 'surface', &
                         'eccentricity', str(eccentricity), "0 < eccentricity <= 1")
            call require(error, finite_in(alpha_deg, -360.0_dp, 360.0_dp), path, 'surface', 'alpha_deg', &
                         str(alpha_deg), "-360 to 360 [degrees]")
            call require(error, finite_in(k_low, 0.0_dp, 1.0e6_dp, open_low=.true.), path, 'surface', 'k_low', &
                         str(k_low), "> 0 (multiples of 2 pi/lx_m)")
            call require(error, finite_in(k_roll, k_low, 1.0e6_dp), path, 'surface', 'k_roll', str(k_roll), ">= k_low")
            call require(error, finite_in(self%k_cut, k_roll, 1.0e6_dp), path, 'surface', 'k_cut', str(self%k_cut), &
                         ">= k_roll")
            call require(error, (finite_in(rms_slope, 0.0_dp, 10.0_dp) .and. finite_in(rms_height_m, 0.0_dp, big)) &
                         .and. (rms_slope > 0.0_dp .neqv. rms_height_m > 0.0_dp), &
                         path, 'surface', 'rms_slope/rms_height_m', str(rms_slope)//"/"//str(rms_height_m), &
                         "exactly one of them > 0 (rms_slope <= 10, rms_height_m <= 1e3 m)")
            call require(error, is_one_of(self%scale_to, [character(len=8) :: 'realised', 'expected']), path, &
                         'surface', 'scale_to', "'"//self%scale_to//"'", "'realised' or 'expected'")
        case ('cosine', 'bisinusoid')
            call require(error, finite_in(amplitude_m, 0.0_dp, big, open_low=.true.), path, 'surface', &
                         'amplitude_m', str(amplitude_m), "> 0 and <= 1e3 [m]")
            call require(error, finite_in(wavelength_m, 0.0_dp, big, open_low=.true.), path, 'surface', &
                         'wavelength_m', str(wavelength_m), "> 0 and <= 1e3 [m]")
            call require(error, finite_in(direction_deg, -360.0_dp, 360.0_dp), path, 'surface', 'direction_deg', &
                         str(direction_deg), "-360 to 360 [degrees]")
        case ('paraboloid', 'cylinder')
            call require(error, finite_in(radius_m, 0.0_dp, 1.0e6_dp, open_low=.true.), path, 'surface', 'radius_m', &
                         str(radius_m), "> 0 and <= 1e6 [m]")
        case ('file')
            call require(error, len(self%file) > 0, path, 'surface', 'file', "''", "the path of an HDF5 file of heights")
        end select
    contains
        subroutine try(lines, stat, msg)
            character(len=*), intent(in) :: lines(:)
            integer, intent(out) :: stat
            character(len=*), intent(out) :: msg
            character(len=max_text + 1) :: kind
            character(len=max_text + 1) :: scale_to
            character(len=max_text + 1) :: file, dataset
            integer(i8) :: seed
            real(dp) :: hurst, eccentricity, alpha_deg, k_low, k_roll, k_cut, rms_slope, rms_height_m
            real(dp) :: amplitude_m, wavelength_m, direction_deg, radius_m
            namelist /surface/ kind, seed, hurst, eccentricity, alpha_deg, k_low, k_roll, k_cut, rms_slope, &
                rms_height_m, scale_to, amplitude_m, wavelength_m, direction_deg, radius_m, file, dataset
            read (lines, nml=surface, iostat=stat, iomsg=msg)
        end subroutine try
    end subroutine read_surface_config

end module veslide_config_surface
