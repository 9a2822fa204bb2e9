!> The hard cases (veslide_scenes) at 64^2: every one converges to 1e-10, and friction has the
!> right sign (zero at rest, positive in motion). The same cases at full size: veslide-bench hard.
module test_veslide_hard
    use veslide_kinds, only: dp
    use veslide_config, only: config_t
    use veslide_case, only: case_t, run_case
    use veslide_scenes, only: hard_case
    use testsuite, only: error_t, unittest_t, new_unittest, check, report
    implicit none
    private
    public :: collect_hard

    integer, parameter :: n = 64

contains

    subroutine collect_hard(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("ratio-11-across-speeds", test_r11), &
            new_unittest("ratio-100-across-speeds", test_r100), &
            new_unittest("ratio-1000-across-speeds", test_r1000), &
            new_unittest("contact-fractions-to-full", test_loads), &
            new_unittest("eccentricity-0.1-at-45", test_ecc), &
            new_unittest("prony-20-terms-12-decades", test_prony), &
            new_unittest("hurst-0.3", test_hurst) &
            ]
    end subroutine collect_hard

    subroutine run_cases(first, last, error)
        integer, intent(in) :: first, last
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        type(case_t) :: c
        character(len=:), allocatable :: name
        real(dp) :: fric
        integer :: k, its
        its = 0
        do k = first, last
            call hard_case(k, n, cfg, name, error); if (allocated(error)) return
            call run_case(cfg, c, error)
            if (allocated(error)) then
                error%message = name//": "//error%message; return
            end if
            call check(error, c%state%converged .and. c%state%residual <= cfg%solver%tolerance, name//": not converged")
            if (allocated(error)) return
            fric = -c%force_pa(1)/cfg%load%mean_pressure_pa
            if (cfg%motion%speed_m_s == 0.0_dp) then
                call check(error, fric == 0.0_dp, name//": friction at rest")
            else
                call check(error, fric > 0.0_dp, name//": friction must resist the motion")
            end if
            if (allocated(error)) return
            its = max(its, c%state%operator_applications)
        end do
        call report("max FFT pairs", real(its, dp))
    end subroutine run_cases

    subroutine test_r11(error)
        type(error_t), allocatable, intent(out) :: error
        call run_cases(1, 7, error)
    end subroutine test_r11

    subroutine test_r100(error)
        type(error_t), allocatable, intent(out) :: error
        call run_cases(8, 14, error)
    end subroutine test_r100

    subroutine test_r1000(error)
        type(error_t), allocatable, intent(out) :: error
        call run_cases(15, 21, error)
    end subroutine test_r1000

    subroutine test_loads(error)
        type(error_t), allocatable, intent(out) :: error
        call run_cases(22, 26, error)
    end subroutine test_loads

    subroutine test_ecc(error)
        type(error_t), allocatable, intent(out) :: error
        call run_cases(27, 27, error)
    end subroutine test_ecc

    subroutine test_prony(error)
        type(error_t), allocatable, intent(out) :: error
        call run_cases(28, 28, error)
    end subroutine test_prony

    subroutine test_hurst(error)
        type(error_t), allocatable, intent(out) :: error
        call run_cases(29, 29, error)
    end subroutine test_hurst

end module test_veslide_hard
