!> &interface: what acts between the rigid surface and the solid besides the normal contact.
!> `shear_coefficient` mu_f is a full-slip Coulomb friction: a shear traction mu_f p on the solid
!> wherever it is pressed, along the rigid surface's velocity (docs/interface.md).
!>
!> Range 0 to 10: dry friction coefficients of rubber, polymers and metals in air stay below about
!> 3 (rubber on smooth glass, the highest of them, 1 to 3); clean metals in vacuum, which reach 10
!> and beyond, seize, and that is no longer full slip. A value above 10 is more likely a
!> percentage or another quantity than a friction coefficient.
module veslide_config_interface
    use veslide_kinds, only: dp
    use veslide_error, only: error_t
    use veslide_strings, only: str
    use veslide_config_common, only: group_text_t, diagnose_read, read_failed, split_lines, require, finite_in
    implicit none
    private
    public :: interface_config_t, read_interface_config, max_shear_coefficient

    !> The largest &interface shear_coefficient accepted
    real(dp), parameter :: max_shear_coefficient = 10.0_dp

    type :: interface_config_t
        real(dp) :: shear_coefficient = 0.0_dp     !! mu_f, full-slip Coulomb friction (0: none) [-]
    end type interface_config_t

    character(len=*), parameter :: names(1) = [character(len=17) :: 'shear_coefficient']
    character(len=*), parameter :: kinds(1) = [character(len=13) :: 'a real number']

contains

    subroutine read_interface_config(self, g, path, error)
        type(interface_config_t), intent(out) :: self
        type(group_text_t), intent(in) :: g
        character(len=*), intent(in) :: path
        type(error_t), allocatable, intent(out) :: error
        real(dp) :: shear_coefficient
        integer :: stat
        character(len=512) :: msg
        character(len=:), allocatable :: lines(:)
        namelist /interface/ shear_coefficient
        shear_coefficient = self%shear_coefficient
        call split_lines(g%text, lines)
        read (lines, nml=interface, iostat=stat, iomsg=msg)
        if (read_failed(stat)) then
            call diagnose_read(stat, msg, path, 'interface', g%body, names, kinds, try, error); return
        end if
        self%shear_coefficient = shear_coefficient
        call require(error, finite_in(shear_coefficient, 0.0_dp, max_shear_coefficient), path, 'interface', &
                     'shear_coefficient', str(shear_coefficient), "0 to 10 (a Coulomb friction coefficient;"// &
                     " 0: no interfacial shear)")
    contains
        subroutine try(lines, stat, msg)
            character(len=*), intent(in) :: lines(:)
            integer, intent(out) :: stat
            character(len=*), intent(out) :: msg
            real(dp) :: shear_coefficient
            namelist /interface/ shear_coefficient
            read (lines, nml=interface, iostat=stat, iomsg=msg)
        end subroutine try
    end subroutine read_interface_config

end module veslide_config_interface
