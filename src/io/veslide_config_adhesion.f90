!> &adhesion: an adhesive contact law (veslide_contact_law), absent by default (the hard wall)
module veslide_config_adhesion
    use veslide_kinds, only: dp
    use veslide_error, only: error_t, fatal_error
    use veslide_strings, only: str
    use veslide_config_common, only: group_text_t, diagnose_read, read_failed, split_lines, require, finite_in
    implicit none
    private
    public :: adhesion_config_t, read_adhesion_config

    !> The law and two of its three parameters (w = sigma0 rho fixes the third)
    type :: adhesion_config_t
        character(len=16) :: law = 'none'            !! 'none', 'exponential' or 'dugdale'
        real(dp) :: energy_j_m2 = 0.0_dp             !! work of adhesion w [J/m^2]
        real(dp) :: range_m = 0.0_dp                 !! range rho [m] (Dugdale: the cohesive zone's opening)
        real(dp) :: stress_pa = 0.0_dp               !! largest attraction sigma0 [Pa]
    end type adhesion_config_t

    character(len=*), parameter :: names(4) = [character(len=11) :: 'law', 'energy_j_m2', 'range_m', 'stress_pa']
    character(len=*), parameter :: kinds(4) = [character(len=13) :: 'a string', 'a real number', 'a real number', &
                                               'a real number']

contains

    subroutine read_adhesion_config(self, g, path, error)
        type(adhesion_config_t), intent(out) :: self
        type(group_text_t), intent(in) :: g
        character(len=*), intent(in) :: path
        type(error_t), allocatable, intent(out) :: error
        character(len=16) :: law
        real(dp) :: energy_j_m2, range_m, stress_pa
        integer :: stat, given
        character(len=512) :: msg
        character(len=:), allocatable :: lines(:)
        namelist /adhesion/ law, energy_j_m2, range_m, stress_pa
        law = self%law; energy_j_m2 = 0.0_dp; range_m = 0.0_dp; stress_pa = 0.0_dp
        call split_lines(g%text, lines)
        read (lines, nml=adhesion, iostat=stat, iomsg=msg)
        if (read_failed(stat)) then
            call diagnose_read(stat, msg, path, 'adhesion', g%body, names, kinds, try, error); return
        end if
        self%law = law
        select case (law)
        case ('none')
            return
        case ('exponential', 'dugdale')
        case default
            call fatal_error(error, "veslide: "//path//": &adhesion law = '"//trim(law)//"' is not a law;"// &
                             " allowed: 'none', 'exponential', 'dugdale'"); return
        end select
        ! each given one in range; exactly two given, or three that agree (w = sigma0 rho)
        if (energy_j_m2 /= 0.0_dp) call require(error, finite_in(energy_j_m2, 0.0_dp, 1.0e3_dp, open_low=.true.), &
                                                path, 'adhesion', 'energy_j_m2', str(energy_j_m2), "> 0 and <= 1e3 [J/m^2]")
        if (allocated(error)) return
        if (range_m /= 0.0_dp) call require(error, finite_in(range_m, 0.0_dp, 1.0_dp, open_low=.true.), path, &
                                            'adhesion', 'range_m', str(range_m), "> 0 and <= 1 [m]")
        if (allocated(error)) return
        if (stress_pa /= 0.0_dp) call require(error, finite_in(stress_pa, 0.0_dp, 1.0e12_dp, open_low=.true.), path, &
                                              'adhesion', 'stress_pa', str(stress_pa), "> 0 and <= 1e12 [Pa]")
        if (allocated(error)) return
        given = count([energy_j_m2 /= 0.0_dp, range_m /= 0.0_dp, stress_pa /= 0.0_dp])
        if (given < 2) then
            call fatal_error(error, "veslide: "//path//": &adhesion law = '"//trim(law)//"' needs two of"// &
                             " energy_j_m2, range_m and stress_pa (energy = stress * range)"); return
        end if
        if (given == 3) then
            if (abs(energy_j_m2 - stress_pa*range_m) > 1.0e-12_dp*energy_j_m2) then
                call fatal_error(error, "veslide: "//path//": &adhesion energy_j_m2 = "//str(energy_j_m2)// &
                                 " differs from stress_pa * range_m = "//str(stress_pa*range_m)// &
                                 " (give two of the three)"); return
            end if
        else if (energy_j_m2 == 0.0_dp) then
            energy_j_m2 = stress_pa*range_m
        else if (range_m == 0.0_dp) then
            range_m = energy_j_m2/stress_pa
        else
            stress_pa = energy_j_m2/range_m
        end if
        self%energy_j_m2 = energy_j_m2; self%range_m = range_m; self%stress_pa = stress_pa
    contains
        subroutine try(lines, stat, msg)
            character(len=*), intent(in) :: lines(:)
            integer, intent(out) :: stat
            character(len=*), intent(out) :: msg
            character(len=16) :: law
            real(dp) :: energy_j_m2, range_m, stress_pa
            namelist /adhesion/ law, energy_j_m2, range_m, stress_pa
            read (lines, nml=adhesion, iostat=stat, iomsg=msg)
        end subroutine try
    end subroutine read_adhesion_config

end module veslide_config_adhesion
