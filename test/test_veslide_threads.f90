!> The thread governor's decisions, on iteration times and context switches given to it
module test_veslide_threads
    use veslide_kinds, only: dp
    use veslide_threads, only: thread_governor_t
    use testsuite, only: error_t, unittest_t, new_unittest, check, report
    implicit none
    private
    public :: collect_threads

contains

    subroutine collect_threads(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("quiet-machine-keeps-all-threads", test_quiet), &
            new_unittest("shared-core-one-thread-faster", test_one_faster), &
            new_unittest("shared-core-all-threads-still-faster", test_all_faster), &
            new_unittest("short-iterations-not-governed", test_short) &
            ]
    end subroutine collect_threads

    !> Fraction of `its` iterations the governor (on 2 threads) runs on one thread, when an
    !> iteration takes t1 s on one thread and t2 s on two, with s1, s2 involuntary switches
    real(dp) function fraction_on_one(its, t1, t2, s1, s2) result(f)
        integer, intent(in) :: its
        real(dp), intent(in) :: t1, t2, s1, s2
        type(thread_governor_t) :: g
        integer :: k, ones
        g%nominal = 2; g%current = 2
        ones = 0
        do k = 1, its
            if (g%current == 1) then
                ones = ones + 1
                call g%decide(t1, s1)
            else
                call g%decide(t2, s2)
            end if
        end do
        f = real(ones, dp)/its
    end function fraction_on_one

    subroutine test_quiet(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp) :: f
        f = fraction_on_one(500, 0.010_dp, 0.006_dp, 0.0_dp, 0.0_dp)
        call report("on one thread", f)
        call check(error, f == 0.0_dp, "left the run's threads on a quiet machine")
    end subroutine test_quiet

    !> A busy process on one core: 10 switches per two-thread iteration, which takes 1.3x the
    !> one-thread time (docs/solver-scaling.md); most iterations must run on one thread
    subroutine test_one_faster(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp) :: f
        f = fraction_on_one(1000, 0.010_dp, 0.013_dp, 0.0_dp, 10.0_dp)
        call report("on one thread", f)
        call check(error, f >= 0.95_dp, "kept two threads though one was faster")
    end subroutine test_one_faster

    !> Switches, but two threads still faster: after probing, two threads nearly all the time
    subroutine test_all_faster(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp) :: f
        f = fraction_on_one(1000, 0.010_dp, 0.007_dp, 0.0_dp, 10.0_dp)
        call report("on one thread", f)
        call check(error, f > 0.0_dp .and. f <= 0.05_dp, "probed one thread too often (or never)")
    end subroutine test_all_faster

    !> Iterations of a millisecond or less are not worth timing: the run's threads stay
    subroutine test_short(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp) :: f
        f = fraction_on_one(500, 0.0005_dp, 0.001_dp, 0.0_dp, 10.0_dp)
        call check(error, f == 0.0_dp, "governed iterations too short to time")
    end subroutine test_short

end module test_veslide_threads
