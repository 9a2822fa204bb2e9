!> &load: the nominal pressure (load control)
module veslide_config_load
    use veslide_kinds, only: dp
    use veslide_error, only: error_t
    use veslide_strings, only: str
    use veslide_config_common, only: namelist_status, require
    implicit none
    private
    public :: load_config_t, read_load_config

    type :: load_config_t
        real(dp) :: mean_pressure_pa = 32.0e3_dp   !! nominal pressure (load control) [Pa]
    end type load_config_t

contains

    subroutine read_load_config(self, u, path, error)
        type(load_config_t), intent(out) :: self
        integer, intent(in) :: u
        character(len=*), intent(in) :: path
        type(error_t), allocatable, intent(out) :: error
        real(dp) :: mean_pressure_pa
        integer :: stat
        character(len=512) :: msg
        namelist /load/ mean_pressure_pa
        mean_pressure_pa = self%mean_pressure_pa
        rewind (u); read (u, nml=load, iostat=stat, iomsg=msg)
        call namelist_status(stat, msg, path, 'load', error); if (allocated(error)) return
        self%mean_pressure_pa = mean_pressure_pa
        call require(error, mean_pressure_pa > 0.0_dp .and. mean_pressure_pa < huge(1.0_dp), path, 'load', &
                     'mean_pressure_pa', str(mean_pressure_pa), "> 0 [Pa]")
    end subroutine read_load_config

end module veslide_config_load
