!> Working precision and the constants used everywhere
module veslide_kinds
    use, intrinsic :: iso_fortran_env, only: dp => real64, i8 => int64
    implicit none
    private
    public :: dp, i8, pi, two_pi, radians

    !> pi to working precision
    real(dp), parameter :: pi = 3.141592653589793238462643383279502884_dp
    !> 2 pi
    real(dp), parameter :: two_pi = 2.0_dp*pi

contains

    !> An angle in degrees (the input's) in radians, deg*pi/180 in that order (the one home of
    !> the conversion: every angle of a case rounds alike)
    elemental real(dp) function radians(deg) result(rad)
        real(dp), intent(in) :: deg
        rad = deg*pi/180.0_dp
    end function radians
end module veslide_kinds
