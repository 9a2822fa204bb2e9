!> &sweep: the lists a study runs through (every combination, speeds innermost)
module veslide_config_sweep
    use veslide_kinds, only: dp, i8
    use veslide_error, only: error_t, fatal_error
    use veslide_strings, only: str
    use veslide_config_common, only: group_text_t, diagnose_read, read_failed, split_lines, require, finite_in, max_list, &
                                     unset_real, is_unset, list_length, check_list
    implicit none
    private
    public :: sweep_config_t, read_sweep_config

    type :: sweep_config_t
        real(dp), allocatable :: speeds(:)          !! speeds [m/s] (a list, or the log range expanded)
        real(dp), allocatable :: alphas(:)          !! PSD angles [deg]
        real(dp), allocatable :: eccentricities(:)  !! PSD eccentricities
        real(dp), allocatable :: pressures(:)       !! nominal pressures [Pa]
        !> rigid-body approaches since first contact [m] (approach control; an adhesive law's)
        real(dp), allocatable :: approaches(:)
        real(dp), allocatable :: temperatures(:)    !! temperatures [degC] (a material with a shift)
        integer(i8), allocatable :: seeds(:)        !! seeds (a list; n_seeds is expanded by the configuration)
        integer :: n_seeds = 0                      !! seeds seed, seed+1, ... when > 0
        logical :: warm_start = .true.              !! start each speed from the previous one's solution
    contains
        procedure :: is_study => sweep_is_study
    end type sweep_config_t

    character(len=*), parameter :: names(12) = [character(len=14) :: 'speeds_m_s', 'speed_min_m_s', &
        'speed_max_m_s', 'n_speeds', 'alphas_deg', 'eccentricities', 'pressures_pa', 'seeds', 'n_seeds', 'warm_start', &
        'temperatures_c', 'approaches_m']
    character(len=*), parameter :: kinds(12) = [character(len=29) :: 'a list of real numbers', 'a real number', &
        'a real number', 'an integer', 'a list of real numbers', 'a list of real numbers', 'a list of real numbers', &
        'a list of integers', 'an integer', 'a logical (.true. or .false.)', 'a list of real numbers', &
        'a list of real numbers']
    integer(i8), parameter :: unset_seed = -huge(1_i8)

contains

    !> Does the configuration describe a study (any list given)?
    pure logical function sweep_is_study(self) result(yes)
        class(sweep_config_t), intent(in) :: self
        yes = size(self%speeds) + size(self%alphas) + size(self%eccentricities) + size(self%pressures) + &
              size(self%temperatures) + size(self%seeds) + self%n_seeds + size(self%approaches) > 0
    end function sweep_is_study

    !> Read &sweep from its text (absent: no study) and check it
    subroutine read_sweep_config(self, g, path, error, adhesive)
        type(sweep_config_t), intent(out) :: self
        type(group_text_t), intent(in) :: g
        character(len=*), intent(in) :: path
        type(error_t), allocatable, intent(out) :: error
        !> an adhesive law (&adhesion): loads may be zero or tensile
        logical, intent(in), optional :: adhesive
        logical :: tensile
        real(dp) :: speeds_m_s(max_list), alphas_deg(max_list), eccentricities(max_list), pressures_pa(max_list)
        real(dp) :: speed_min_m_s, speed_max_m_s, temperatures_c(max_list), approaches_m(max_list)
        integer :: n_speeds, n_seeds, stat, k, ns
        integer(i8) :: seeds(max_list)
        logical :: warm_start
        character(len=512) :: msg
        character(len=:), allocatable :: lines(:)
        namelist /sweep/ speeds_m_s, speed_min_m_s, speed_max_m_s, n_speeds, alphas_deg, eccentricities, &
            pressures_pa, seeds, n_seeds, warm_start, temperatures_c, approaches_m
        temperatures_c = unset_real(); approaches_m = unset_real()
        speeds_m_s = unset_real(); alphas_deg = unset_real(); eccentricities = unset_real()
        pressures_pa = unset_real(); seeds = unset_seed
        speed_min_m_s = unset_real(); speed_max_m_s = unset_real(); n_speeds = 0; n_seeds = 0
        warm_start = self%warm_start
        call split_lines(g%text, lines)
        read (lines, nml=sweep, iostat=stat, iomsg=msg)
        if (read_failed(stat)) then
            call diagnose_read(stat, msg, path, 'sweep', g%body, names, kinds, try, error); return
        end if
        self%warm_start = warm_start
        call check_list(error, speeds_m_s, path, 'sweep', 'speeds_m_s')
        call check_list(error, alphas_deg, path, 'sweep', 'alphas_deg')
        call check_list(error, eccentricities, path, 'sweep', 'eccentricities')
        call check_list(error, pressures_pa, path, 'sweep', 'pressures_pa')
        call check_list(error, temperatures_c, path, 'sweep', 'temperatures_c')
        call check_list(error, approaches_m, path, 'sweep', 'approaches_m')
        if (allocated(error)) return
        ns = count(seeds /= unset_seed)
        if (any(seeds(1:ns) == unset_seed) .or. any(seeds(ns + 1:) /= unset_seed)) then
            call fatal_error(error, "veslide: "//path//": &sweep seeds has a gap: give a contiguous list"); return
        end if
        self%speeds = speeds_m_s(1:list_length(speeds_m_s))
        self%alphas = alphas_deg(1:list_length(alphas_deg))
        self%eccentricities = eccentricities(1:list_length(eccentricities))
        self%pressures = pressures_pa(1:list_length(pressures_pa))
        self%temperatures = temperatures_c(1:list_length(temperatures_c))
        self%approaches = approaches_m(1:list_length(approaches_m))
        self%seeds = seeds(1:ns)
        if (n_speeds /= 0 .or. .not. is_unset(speed_min_m_s) .or. .not. is_unset(speed_max_m_s)) then
            if (n_speeds == 0) then
                call fatal_error(error, "veslide: "//path//": &sweep speed_min_m_s/speed_max_m_s need n_speeds"// &
                    " (allowed: 2 <= n_speeds <= 1000 speeds from speed_min_m_s to speed_max_m_s)"); return
            end if
            if (size(self%speeds) > 0 .or. n_speeds < 2 .or. n_speeds > 1000 .or. &
                .not. (finite_in(speed_min_m_s, 0.0_dp, 1.0e12_dp, open_low=.true.) .and. &
                       finite_in(speed_max_m_s, 0.0_dp, 1.0e12_dp) .and. speed_max_m_s > speed_min_m_s)) then
                call fatal_error(error, "veslide: "//path//": &sweep n_speeds, speed_min_m_s, speed_max_m_s = "// &
                    str(n_speeds)//", "//value_or_unset(speed_min_m_s)//", "//value_or_unset(speed_max_m_s)// &
                    " are out of range (allowed: 2 <= n_speeds <= 1000, 0 < speed_min_m_s < speed_max_m_s"// &
                    " <= 1e12, and no speeds_m_s list)"); return
            end if
            self%speeds = [(speed_min_m_s*(speed_max_m_s/speed_min_m_s)**(real(k, dp)/(n_speeds - 1)), &
                            k = 0, n_speeds - 1)]
        end if
        if (n_seeds /= 0) then
            if (size(self%seeds) > 0 .or. n_seeds < 1 .or. n_seeds > 100000) then
                call fatal_error(error, "veslide: "//path//": &sweep n_seeds = "//str(n_seeds)// &
                    " is out of range (allowed: 1 to 100000, and no seeds list); seeds are seed, seed+1, ..."); return
            end if
            self%n_seeds = n_seeds
        end if
        do k = 1, size(self%speeds)
            call require(error, finite_in(self%speeds(k), 0.0_dp, 1.0e12_dp), path, 'sweep', &
                         'speeds_m_s('//str(k)//')', str(self%speeds(k)), "0 to 1e12 [m/s]")
        end do
        do k = 1, size(self%alphas)
            call require(error, finite_in(self%alphas(k), -360.0_dp, 360.0_dp), path, 'sweep', &
                         'alphas_deg('//str(k)//')', str(self%alphas(k)), "-360 to 360 [degrees]")
        end do
        do k = 1, size(self%eccentricities)
            call require(error, finite_in(self%eccentricities(k), 0.0_dp, 1.0_dp, open_low=.true.), path, 'sweep', &
                         'eccentricities('//str(k)//')', str(self%eccentricities(k)), "0 < eccentricity <= 1")
        end do
        tensile = .false.; if (present(adhesive)) tensile = adhesive
        do k = 1, size(self%pressures)
            if (tensile) then
                call require(error, finite_in(self%pressures(k), -1.0e12_dp, 1.0e12_dp), path, 'sweep', &
                             'pressures_pa('//str(k)//')', str(self%pressures(k)), ">= -1e12 and <= 1e12 [Pa]")
            else
                call require(error, finite_in(self%pressures(k), 0.0_dp, 1.0e12_dp, open_low=.true.), path, 'sweep', &
                             'pressures_pa('//str(k)//')', str(self%pressures(k)), "> 0 and <= 1e12 [Pa] (zero or"// &
                             " tensile only with &adhesion)")
            end if
        end do
        if (size(self%approaches) > 0) then
            ! approach control along a load path (veslide_study): an adhesive law's
            if (.not. tensile) then
                call fatal_error(error, "veslide: "//path//": &sweep approaches_m (approach control) needs an"// &
                    " adhesive law (&adhesion law = 'exponential' or 'dugdale'); give pressures_pa instead"); return
            end if
            if (size(self%pressures) > 0) then
                call fatal_error(error, "veslide: "//path//": &sweep gives both pressures_pa and approaches_m;"// &
                                 " give one (a path of loads, or of approaches)"); return
            end if
        end if
        do k = 1, size(self%approaches)
            call require(error, finite_in(self%approaches(k), -1.0_dp, 1.0_dp), path, 'sweep', &
                         'approaches_m('//str(k)//')', str(self%approaches(k)), ">= -1 and <= 1 [m] (the rigid-body"// &
                         " approach since first contact)")
        end do
        do k = 1, size(self%temperatures)
            call require(error, finite_in(self%temperatures(k), -273.15_dp, 1.0e4_dp, open_low=.true.), path, 'sweep', &
                         'temperatures_c('//str(k)//')', str(self%temperatures(k)), "> -273.15 [C]")
        end do
    contains
        function value_or_unset(x) result(s)
            real(dp), intent(in) :: x
            character(len=:), allocatable :: s
            if (is_unset(x)) then
                s = '(unset)'
            else
                s = str(x)
            end if
        end function value_or_unset
        subroutine try(lines, stat, msg)
            character(len=*), intent(in) :: lines(:)
            integer, intent(out) :: stat
            character(len=*), intent(out) :: msg
            real(dp) :: speeds_m_s(max_list), alphas_deg(max_list), eccentricities(max_list), pressures_pa(max_list)
            real(dp) :: speed_min_m_s, speed_max_m_s, temperatures_c(max_list), approaches_m(max_list)
            integer :: n_speeds, n_seeds
            integer(i8) :: seeds(max_list)
            logical :: warm_start
            namelist /sweep/ speeds_m_s, speed_min_m_s, speed_max_m_s, n_speeds, alphas_deg, eccentricities, &
                pressures_pa, seeds, n_seeds, warm_start, temperatures_c, approaches_m
            read (lines, nml=sweep, iostat=stat, iomsg=msg)
        end subroutine try
    end subroutine read_sweep_config

end module veslide_config_sweep
