!> &load: the nominal pressure (load control; zero or tensile with an adhesive law), or with an
!> adhesive law the rigid-body approach (approach control)
module veslide_config_load
    use veslide_kinds, only: dp
    use veslide_error, only: error_t, fatal_error
    use veslide_strings, only: str
    use veslide_config_common, only: group_text_t, diagnose_read, read_failed, split_lines, require, finite_in
    implicit none
    private
    public :: load_config_t, read_load_config

    type :: load_config_t
        real(dp) :: mean_pressure_pa = 32.0e3_dp   !! nominal pressure (load control) [Pa]
        !> approach control (an adhesive law's): the rigid-body approach since first contact [m];
        !> huge() when not given (load control)
        real(dp) :: approach_m = huge(1.0_dp)
    end type load_config_t

    character(len=*), parameter :: names(2) = [character(len=16) :: 'mean_pressure_pa', 'approach_m']
    character(len=*), parameter :: kinds(2) = [character(len=13) :: 'a real number', 'a real number']

contains

    subroutine read_load_config(self, g, path, error, adhesive)
        type(load_config_t), intent(out) :: self
        type(group_text_t), intent(in) :: g
        character(len=*), intent(in) :: path
        type(error_t), allocatable, intent(out) :: error
        !> an adhesive law (&adhesion): the load may be zero or tensile
        logical, intent(in), optional :: adhesive
        real(dp) :: mean_pressure_pa, approach_m
        integer :: stat
        character(len=512) :: msg
        character(len=:), allocatable :: lines(:)
        logical :: tensile
        namelist /load/ mean_pressure_pa, approach_m
        mean_pressure_pa = huge(1.0_dp); approach_m = huge(1.0_dp)
        call split_lines(g%text, lines)
        read (lines, nml=load, iostat=stat, iomsg=msg)
        if (read_failed(stat)) then
            call diagnose_read(stat, msg, path, 'load', g%body, names, kinds, try, error); return
        end if
        tensile = .false.; if (present(adhesive)) tensile = adhesive
        if (approach_m /= huge(1.0_dp)) then
            ! approach control: an adhesive law's (veslide_solver_gcg), instead of the load
            if (.not. tensile) then
                call fatal_error(error, "veslide: "//path//": &load approach_m (approach control) needs an adhesive"// &
                                 " law (&adhesion law = 'exponential' or 'dugdale'); give mean_pressure_pa instead")
                return
            end if
            if (mean_pressure_pa /= huge(1.0_dp)) then
                call fatal_error(error, "veslide: "//path//": &load gives both mean_pressure_pa and approach_m;"// &
                                 " give one (the load, or the approach)"); return
            end if
            call require(error, finite_in(approach_m, -1.0_dp, 1.0_dp), path, 'load', 'approach_m', str(approach_m), &
                         ">= -1 and <= 1 [m] (the rigid-body approach since first contact)")
            self%approach_m = approach_m
            self%mean_pressure_pa = 0.0_dp
            return
        end if
        if (mean_pressure_pa == huge(1.0_dp)) mean_pressure_pa = self%mean_pressure_pa
        self%mean_pressure_pa = mean_pressure_pa
        if (present(adhesive)) then
            if (adhesive) then
                call require(error, finite_in(mean_pressure_pa, -1.0e12_dp, 1.0e12_dp), path, 'load', &
                             'mean_pressure_pa', str(mean_pressure_pa), ">= -1e12 and <= 1e12 [Pa] (tensile below 0:"// &
                             " &adhesion)")
                return
            end if
        end if
        call require(error, finite_in(mean_pressure_pa, 0.0_dp, 1.0e12_dp, open_low=.true.), path, 'load', &
                     'mean_pressure_pa', str(mean_pressure_pa), "> 0 and <= 1e12 [Pa] (zero or tensile only"// &
                     " with &adhesion)")
    contains
        subroutine try(lines, stat, msg)
            character(len=*), intent(in) :: lines(:)
            integer, intent(out) :: stat
            character(len=*), intent(out) :: msg
            real(dp) :: mean_pressure_pa, approach_m
            namelist /load/ mean_pressure_pa, approach_m
            read (lines, nml=load, iostat=stat, iomsg=msg)
        end subroutine try
    end subroutine read_load_config

end module veslide_config_load
