!> &motion: the sliding velocity of the rigid surface relative to the solid
module veslide_config_motion
    use veslide_kinds, only: dp
    use veslide_error, only: error_t
    use veslide_strings, only: str
    use veslide_config_common, only: group_text_t, diagnose_read, read_failed, split_lines, require, finite_in
    implicit none
    private
    public :: motion_config_t, read_motion_config

    type :: motion_config_t
        real(dp) :: speed_m_s = 0.0_dp             !! sliding speed of the rigid surface [m/s]
        real(dp) :: direction_deg = 0.0_dp         !! direction of v from x [deg]
    end type motion_config_t

    character(len=*), parameter :: names(2) = [character(len=13) :: 'speed_m_s', 'direction_deg']
    character(len=*), parameter :: kinds(2) = [character(len=13) :: 'a real number', 'a real number']

contains

    subroutine read_motion_config(self, g, path, error)
        type(motion_config_t), intent(out) :: self
        type(group_text_t), intent(in) :: g
        character(len=*), intent(in) :: path
        type(error_t), allocatable, intent(out) :: error
        real(dp) :: speed_m_s, direction_deg
        integer :: stat
        character(len=512) :: msg
        character(len=:), allocatable :: lines(:)
        namelist /motion/ speed_m_s, direction_deg
        speed_m_s = self%speed_m_s; direction_deg = self%direction_deg
        call split_lines(g%text, lines)
        read (lines, nml=motion, iostat=stat, iomsg=msg)
        if (read_failed(stat)) then
            call diagnose_read(stat, msg, path, 'motion', g%body, names, kinds, try, error); return
        end if
        self%speed_m_s = speed_m_s; self%direction_deg = direction_deg
        call require(error, finite_in(speed_m_s, 0.0_dp, 1.0e12_dp), path, 'motion', 'speed_m_s', str(speed_m_s), &
                     "0 to 1e12 [m/s]")
        call require(error, finite_in(direction_deg, -360.0_dp, 360.0_dp), path, 'motion', 'direction_deg', &
                     str(direction_deg), "-360 to 360 [degrees]")
    contains
        subroutine try(lines, stat, msg)
            character(len=*), intent(in) :: lines(:)
            integer, intent(out) :: stat
            character(len=*), intent(out) :: msg
            real(dp) :: speed_m_s, direction_deg
            namelist /motion/ speed_m_s, direction_deg
            read (lines, nml=motion, iostat=stat, iomsg=msg)
        end subroutine try
    end subroutine read_motion_config

end module veslide_config_motion
