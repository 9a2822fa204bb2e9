!> &sweep: the lists a study runs through (every combination, speeds innermost)
module veslide_config_sweep
    use veslide_kinds, only: dp, i8
    use veslide_error, only: error_t, fatal_error
    use veslide_strings, only: str
    use veslide_config_common, only: namelist_status, require, max_list
    implicit none
    private
    public :: sweep_config_t, read_sweep_config

    type :: sweep_config_t
        real(dp), allocatable :: speeds(:)          !! speeds [m/s] (a list, or the log range expanded)
        real(dp), allocatable :: alphas(:)          !! PSD angles [deg]
        real(dp), allocatable :: eccentricities(:)  !! PSD eccentricities
        real(dp), allocatable :: pressures(:)       !! nominal pressures [Pa]
        integer(i8), allocatable :: seeds(:)        !! seeds (a list; n_seeds is expanded by the configuration)
        integer :: n_seeds = 0                      !! seeds seed, seed+1, ... when > 0
        logical :: warm_start = .true.              !! start each speed from the previous one's solution
    contains
        procedure :: is_study => sweep_is_study
    end type sweep_config_t

    real(dp), parameter :: unset = -huge(1.0_dp)

contains

    !> Does the configuration describe a study (any list given)?
    pure logical function sweep_is_study(self) result(yes)
        class(sweep_config_t), intent(in) :: self
        yes = size(self%speeds) + size(self%alphas) + size(self%eccentricities) + size(self%pressures) + &
              size(self%seeds) + self%n_seeds > 0
    end function sweep_is_study

    !> Read &sweep from the open namelist file `u` (absent: no study) and check it
    subroutine read_sweep_config(self, u, path, error)
        type(sweep_config_t), intent(out) :: self
        integer, intent(in) :: u
        character(len=*), intent(in) :: path
        type(error_t), allocatable, intent(out) :: error
        real(dp) :: speeds_m_s(max_list), alphas_deg(max_list), eccentricities(max_list), pressures_pa(max_list)
        real(dp) :: speed_min_m_s, speed_max_m_s, big
        integer :: n_speeds, n_seeds, stat, k
        integer(i8) :: seeds(max_list)
        logical :: warm_start
        character(len=512) :: msg
        namelist /sweep/ speeds_m_s, speed_min_m_s, speed_max_m_s, n_speeds, alphas_deg, eccentricities, &
            pressures_pa, seeds, n_seeds, warm_start
        speeds_m_s = unset; alphas_deg = unset; eccentricities = unset; pressures_pa = unset
        seeds = -huge(1_i8); speed_min_m_s = 0; speed_max_m_s = 0; n_speeds = 0; n_seeds = 0
        warm_start = self%warm_start
        rewind (u); read (u, nml=sweep, iostat=stat, iomsg=msg)
        call namelist_status(stat, msg, path, 'sweep', error); if (allocated(error)) return
        self%warm_start = warm_start
        self%speeds = pack(speeds_m_s, speeds_m_s /= unset)
        self%alphas = pack(alphas_deg, alphas_deg /= unset)
        self%eccentricities = pack(eccentricities, eccentricities /= unset)
        self%pressures = pack(pressures_pa, pressures_pa /= unset)
        self%seeds = pack(seeds, seeds /= -huge(1_i8))
        if (n_speeds /= 0) then
            if (size(self%speeds) > 0 .or. n_speeds < 2 .or. n_speeds > 1000 .or. &
                .not. (speed_min_m_s > 0.0_dp .and. speed_max_m_s > speed_min_m_s)) then
                call fatal_error(error, "veslide: "//path//": &sweep n_speeds, speed_min_m_s, speed_max_m_s"// &
                    " are out of range (allowed: 2 <= n_speeds <= 1000, 0 < speed_min_m_s < speed_max_m_s,"// &
                    " and no speeds_m_s list)"); return
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
        big = huge(1.0_dp)
        call require(error, all(self%speeds >= 0.0_dp .and. self%speeds < big), path, 'sweep', 'speeds_m_s', "", &
                     "every speed >= 0 [m/s]")
        call require(error, all(abs(self%alphas) <= 360.0_dp), path, 'sweep', 'alphas_deg', "", &
                     "every angle -360 to 360 [degrees]")
        call require(error, all(self%eccentricities > 0.0_dp .and. self%eccentricities <= 1.0_dp), path, 'sweep', &
                     'eccentricities', "", "every value 0 < eccentricity <= 1")
        call require(error, all(self%pressures > 0.0_dp .and. self%pressures < big), path, 'sweep', 'pressures_pa', &
                     "", "every pressure > 0 [Pa]")
    end subroutine read_sweep_config

end module veslide_config_sweep
