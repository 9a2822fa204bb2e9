!> Wall-clock time for the timings recorded with every result
module veslide_clock
    use veslide_kinds, only: dp, i8
    implicit none
    private
    public :: wall_seconds

contains

    !> Seconds since an arbitrary origin (system_clock at its finest rate)
    real(dp) function wall_seconds() result(t)
        integer(i8) :: count, rate
        call system_clock(count, rate)
        t = real(count, dp)/real(rate, dp)
    end function wall_seconds

end module veslide_clock
