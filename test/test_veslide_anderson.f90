!> Anderson acceleration on its own: on a linear fixed-point map it is GMRES in disguise
!> (exact after n + 1 steps with memory n), far ahead of the plain iteration; and its history
!> management (reset, the plain step from the previous point)
module test_veslide_anderson
    use veslide_kinds, only: dp
    use veslide_anderson, only: anderson_t
    use testsuite, only: error_t, unittest_t, new_unittest, check, report
    implicit none
    private
    public :: collect_anderson

    integer, parameter :: n = 8

contains

    subroutine collect_anderson(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("linear-map-solved-in-n-plus-one-steps", test_linear), &
            new_unittest("memory-zero-is-the-plain-step", test_plain), &
            new_unittest("rejected-step-restarts-from-previous", test_restart) &
            ]
    end subroutine collect_anderson

    !> g(z) = M z + b with M a contraction (spectral radius 0.95, not normal); f = g(z) - z
    subroutine linear_map(m, b)
        real(dp), intent(out) :: m(n, n), b(n)
        integer :: i
        m = 0
        do i = 1, n
            m(i, i) = 0.95_dp*cos(0.7_dp*i)
            if (i < n) m(i, i + 1) = 0.3_dp
        end do
        b = [(1.0_dp/i, i = 1, n)]
    end subroutine linear_map

    subroutine test_linear(error)
        type(error_t), allocatable, intent(out) :: error
        type(anderson_t) :: aa
        real(dp) :: m(n, n), b(n), z(n), zp(n), f(n), fix(n), a(n, n)
        integer :: k, steps_aa, steps_plain
        logical :: acc
        call linear_map(m, b)
        ! the fixed point solves (I - M) z = b
        a = -m
        do k = 1, n
            a(k, k) = a(k, k) + 1
        end do
        fix = solve(a, b)
        call aa%init(n, 1, n, .false.)
        z = 0; steps_aa = 0
        do k = 1, 100
            f = matmul(m, z) + b - z
            if (norm2(z - fix) <= 1.0e-10_dp*norm2(fix)) exit
            acc = aa%step(z, f); steps_aa = k
        end do
        zp = 0; steps_plain = 0
        do k = 1, 100000
            if (norm2(zp - fix) <= 1.0e-10_dp*norm2(fix)) exit
            zp = matmul(m, zp) + b; steps_plain = k
        end do
        call report("steps, Anderson(n)", real(steps_aa, dp)); call report("steps, plain", real(steps_plain, dp))
        call check(error, steps_aa <= n + 2, "Anderson(n) needs more than n + 2 steps on a linear map")
        if (allocated(error)) return
        call check(error, steps_plain > 10*steps_aa, "no acceleration over the plain iteration")
    end subroutine test_linear

    subroutine test_plain(error)
        type(error_t), allocatable, intent(out) :: error
        type(anderson_t) :: aa
        real(dp) :: z(n), f(n)
        logical :: acc
        integer :: k
        call aa%init(n, 1, 0, .false.)
        z = 1; f = [(real(k, dp), k = 1, n)]
        acc = aa%step(z, f); acc = aa%step(z, f)
        call check(error, .not. acc .and. all(z == 1 + 2*f), "memory 0 must be z <- z + f")
    end subroutine test_plain

    subroutine test_restart(error)
        type(error_t), allocatable, intent(out) :: error
        type(anderson_t) :: aa
        real(dp) :: z(n), z0(n), f0(n), f1(n), step
        logical :: acc
        integer :: k
        call aa%init(n, 1, 3, .false.)
        z0 = [(real(k, dp), k = 1, n)]; f0 = 0.5_dp; f1 = [(0.1_dp*k, k = 1, n)]
        z = z0
        acc = aa%step(z, f0)                        ! plain: z = z0 + f0
        call check(error, .not. acc .and. all(z == z0 + f0), "first step is plain"); if (allocated(error)) return
        acc = aa%step(z, f1)                        ! accelerated from (z0 + f0, f1)
        call check(error, acc, "second step is accelerated"); if (allocated(error)) return
        step = maxval(abs(z - (z0 + f0)))
        call aa%plain_step_from_previous(z)         ! rejected: back to (z0 + f0) + f1
        ! the previous point and its residual are kept in double precision: the plain step from
        ! them is the one the first step would have taken, exactly
        call report("accelerated step's size", step)
        call check(error, all(z == (z0 + f0) + f1), "plain step from the previous point")
        if (allocated(error)) return
        acc = aa%step(z, f1)
        call check(error, .not. acc, "history cleared after a rejected step")
    end subroutine test_restart

    !> Gaussian elimination with partial pivoting (a small dense reference)
    function solve(a0, b0) result(x)
        real(dp), intent(in) :: a0(:, :), b0(:)
        real(dp) :: x(size(b0)), a(size(b0), size(b0)), b(size(b0)), t(size(b0)), s
        integer :: i, k, p
        a = a0; b = b0
        do k = 1, size(b)
            p = maxloc(abs(a(k:, k)), dim=1) + k - 1
            t = a(k, :); a(k, :) = a(p, :); a(p, :) = t
            s = b(k); b(k) = b(p); b(p) = s
            do i = k + 1, size(b)
                s = a(i, k)/a(k, k)
                a(i, :) = a(i, :) - s*a(k, :); b(i) = b(i) - s*b(k)
            end do
        end do
        do k = size(b), 1, -1
            x(k) = (b(k) - dot_product(a(k, k + 1:), x(k + 1:)))/a(k, k)
        end do
    end function solve

end module test_veslide_anderson
