!> &motion: the sliding velocity of the rigid surface relative to the solid
module veslide_config_motion
    use veslide_kinds, only: dp
    use veslide_error, only: error_t
    use veslide_strings, only: str
    use veslide_config_common, only: namelist_status, require
    implicit none
    private
    public :: motion_config_t, read_motion_config

    type :: motion_config_t
        real(dp) :: speed_m_s = 0.0_dp             !! sliding speed of the rigid surface [m/s]
        real(dp) :: direction_deg = 0.0_dp         !! direction of v from x [deg]
    end type motion_config_t

contains

    subroutine read_motion_config(self, u, path, error)
        type(motion_config_t), intent(out) :: self
        integer, intent(in) :: u
        character(len=*), intent(in) :: path
        type(error_t), allocatable, intent(out) :: error
        real(dp) :: speed_m_s, direction_deg
        integer :: stat
        character(len=512) :: msg
        namelist /motion/ speed_m_s, direction_deg
        speed_m_s = self%speed_m_s; direction_deg = self%direction_deg
        rewind (u); read (u, nml=motion, iostat=stat, iomsg=msg)
        call namelist_status(stat, msg, path, 'motion', error); if (allocated(error)) return
        self%speed_m_s = speed_m_s; self%direction_deg = direction_deg
        call require(error, speed_m_s >= 0.0_dp .and. speed_m_s < huge(1.0_dp), path, 'motion', 'speed_m_s', &
                     str(speed_m_s), ">= 0 [m/s]")
        call require(error, abs(direction_deg) <= 360.0_dp, path, 'motion', 'direction_deg', str(direction_deg), &
                     "-360 to 360 [degrees]")
    end subroutine read_motion_config

end module veslide_config_motion
