!> Random numbers: the xoshiro stream and the counter-based Philox draws that build surfaces
module test_veslide_rng
    use veslide_kinds, only: dp, i8
    use veslide_rng, only: rng_t, normal_pair_at, philox4x32
    use testsuite, only: error_t, unittest_t, new_unittest, check, report
    implicit none
    private
    public :: collect_rng

contains

    subroutine collect_rng(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("rng-reproducible", test_rng), &
            new_unittest("rng-normal-moments", test_rng_moments), &
            new_unittest("philox-known-answers", test_philox_kat), &
            new_unittest("streams-independent", test_streams) &
            ]
    end subroutine collect_rng

    subroutine test_rng(error)
        type(error_t), allocatable, intent(out) :: error
        type(rng_t) :: a, b, c
        integer :: k
        real(dp) :: z1, z2, y1, y2
        call a%seed(42_i8); call b%seed(42_i8); call c%seed(43_i8)
        do k = 1, 1000
            if (a%uniform() /= b%uniform()) then
                call check(error, .false., "same seed, different stream"); return
            end if
        end do
        call check(error, a%uniform() /= c%uniform(), "different seeds, same number"); if (allocated(error)) return
        call normal_pair_at(5_i8, 3, -2, z1, z2)
        call normal_pair_at(6_i8, 7, 1, y1, y2)       ! an unrelated call in between changes nothing
        call normal_pair_at(5_i8, 3, -2, y1, y2)
        call check(error, z1 == y1 .and. z2 == y2, "counter-based draw not reproducible")
    end subroutine test_rng

    !> Mean, variance and kurtosis of 2e5 counter-based normals within 5 standard errors
    subroutine test_rng_moments(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 100000
        real(dp) :: s1, s2, s4, z1, z2
        integer :: k
        s1 = 0; s2 = 0; s4 = 0
        do k = 1, n
            call normal_pair_at(11_i8, k, -k, z1, z2)
            s1 = s1 + z1 + z2; s2 = s2 + z1**2 + z2**2; s4 = s4 + z1**4 + z2**4
        end do
        s1 = s1/(2*n); s2 = s2/(2*n); s4 = s4/(2*n)
        call report("mean", s1); call report("var-1", s2 - 1); call report("m4-3", s4 - 3)
        ! standard errors: mean 1/sqrt(N), variance sqrt(2/N), 4th moment sqrt(96/N)
        call check(error, abs(s1) < 5/sqrt(2.0_dp*n), "mean"); if (allocated(error)) return
        call check(error, abs(s2 - 1) < 5*sqrt(2.0_dp/(2*n)), "variance"); if (allocated(error)) return
        call check(error, abs(s4 - 3) < 5*sqrt(96.0_dp/(2*n)), "fourth moment")
    end subroutine test_rng_moments

    !> Philox4x32-10 against the known-answer vectors of the Random123 distribution
    subroutine test_philox_kat(error)
        type(error_t), allocatable, intent(out) :: error
        integer(i8) :: x(4)
        x = philox4x32([0_i8, 0_i8, 0_i8, 0_i8], [0_i8, 0_i8])
        call check(error, all(x == [int(z'6627e8d5', i8), int(z'e169c58d', i8), int(z'bc57ac4c', i8), &
                                    int(z'9b00dbd8', i8)]), "Philox KAT, zero counter and key")
        if (allocated(error)) return
        x = philox4x32([4294967295_i8, 4294967295_i8, 4294967295_i8, 4294967295_i8], [4294967295_i8, 4294967295_i8])
        call check(error, all(x == [int(z'408f276d', i8), int(z'41c83b0e', i8), int(z'a20bc7c6', i8), &
                                    int(z'6d5451fd', i8)]), "Philox KAT, all ones")
        if (allocated(error)) return
        x = philox4x32([int(z'243f6a88', i8), int(z'85a308d3', i8), int(z'13198a2e', i8), int(z'03707344', i8)], &
                       [int(z'a4093822', i8), int(z'299f31d0', i8)])
        call check(error, all(x == [int(z'd16cfe09', i8), int(z'94fdcceb', i8), int(z'5001e420', i8), &
                                    int(z'24126ea1', i8)]), "Philox KAT, digits of pi")
    end subroutine test_philox_kat

    !> Draws of another stream (the third counter word) are a different family: uncorrelated
    subroutine test_streams(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 20000
        real(dp) :: a(n), b(n), z2
        integer :: k
        do k = 1, n
            call normal_pair_at(3_i8, k, 2*k, a(k), z2)
            call normal_pair_at(3_i8, k, 2*k, b(k), z2, stream=1)
        end do
        call report("correlation", sum(a*b)/sqrt(sum(a*a)*sum(b*b)))
        call check(error, abs(sum(a*b)/sqrt(sum(a*a)*sum(b*b))) < 4/sqrt(real(n, dp)), "streams correlated")
    end subroutine test_streams

end module test_veslide_rng
