!> Preconditioned Douglas-Rachford splitting ('pdr'): the splitting of `solver_dr` carried out
!> in the metric of the operator's modulus |K|, with the metric projection onto the constraints
!> solved by the bound-constrained CG of `solver_bccg`. For the viscoelastic (non-symmetric)
!> problem in motion; its outer iteration count does not depend on the grid.
!>
!> The problem is the variational inequality: p in C = {p >= 0, mean p = p_mean} with
!> <K p - h, p' - p> >= 0 for all p' in C. In the inner product <a, b>_M = <a, M b>, M the
!> symmetric positive multiplier |K(q)| (zero on the mean mode, where C fixes p), it reads
!> 0 in T(p) + N_C(p) with T(p) = M^-1 (K p - h), and T is a Fourier multiplier of symbol
!> K/|K| = exp(i delta(q)) (delta the loss angle of the mode): bounded and monotone whatever the
!> grid, where the plain splitting works with the symbol K itself, whose spread grows with the
!> grid. Douglas-Rachford in that metric, in units p/p_mean, h/h_s, with step gamma:
!>   x = (I + gamma T)^-1 z:   x^ = (M z^ + gamma h^)/(M + gamma K^)   (one FFT pair)
!>   y = argmin over C of |2x - z - y|_M: an elastic contact problem with the operator M and the
!>       heights M (2x - z), solved by BCCG warm-started from the previous y
!>   z <- z + y - x, accelerated by Anderson mixing (`anderson_t`).
!> At the fixed point x = y = p. The inner problems are solved to a tolerance that follows the
!> outer residual (a tenth of it, and never below a third of the target); every outer
!> iteration confirms the residual of y on a fresh K y. Measured in docs/solver-scaling.md.
module veslide_solver_pdr
    use, intrinsic :: iso_c_binding, only: c_f_pointer, c_loc
    use veslide_kinds, only: dp
    use veslide_fftw, only: fft2d_t
    use veslide_contact, only: contact_problem_t, contact_state_t, residual_measures
    use veslide_solver_options, only: solver_options_t
    use veslide_anderson, only: anderson_t
    use veslide_solver_bccg, only: bccg_t
    implicit none
    private
    public :: preconditioned_douglas_rachford

contains

    subroutine preconditioned_douglas_rachford(problem, fft, opts, state, gap0)
        type(contact_problem_t), intent(in) :: problem
        type(fft2d_t), intent(inout) :: fft
        type(solver_options_t), intent(in) :: opts
        !> on entry the starting pressure (problem%start); on exit the solution
        type(contact_state_t), intent(inout) :: state
        !> gap of the starting pressure [m] (default: zero gap)
        real(dp), intent(in), optional :: gap0(:, :)
        real(dp), parameter :: inner_fraction = 0.2_dp
        type(bccg_t) :: b
        type(anderson_t) :: aa
        complex(dp), allocatable :: kn(:, :), am(:, :), cm(:, :), hk(:, :)
        real(dp), allocatable :: mn(:, :), y(:, :), x(:, :)
        real(dp), allocatable, target :: zz(:, :), ff(:, :)
        real(dp), pointer :: z(:), f(:)
        real(dp) :: hs, p_mean, gamma, n, itol, res_prev, d, s1, gmin, spg, sp, g
        integer :: nx, ny, nq, its, i, j, nc
        logical :: accelerated

        nx = size(problem%hc, 1); ny = size(problem%hc, 2); nq = nx/2 + 1
        n = real(nx, dp)*ny
        hs = problem%height_scale_m
        p_mean = problem%p_mean_pa
        state%method = 'pdr'
        gamma = opts%step
        if (.not. (gamma > 0.0_dp)) gamma = 1.0_dp

        ! multipliers: K/N and M/N = |K|/N, dimensionless; the resolvent's two parts
        kn = problem%kernel%multiplier(p_mean/hs)
        mn = abs(kn)
        call b%init(fft, mn, problem%kernel%grid)
        allocate (am(nq, ny), cm(nq, ny))
        fft%x = problem%hc/hs
        call fft%forward()
        hk = fft%k
        b%pairs = 0.5_dp
        call set_step()

        ! start: y = p, z = p + gamma M^-1 g (g the gap of the start, when given)
        allocate (zz(nx, ny), ff(nx, ny), x(nx, ny))
        y = state%p/p_mean
        zz = y
        if (present(gap0)) then
            fft%x = gap0/hs
            call fft%forward()
            where (mn > 0.0_dp)
                fft%k = fft%k*(gamma/(mn*n*n))
            elsewhere
                fft%k = (0.0_dp, 0.0_dp)
            end where
            call fft%backward_unscaled()
            zz = zz + fft%x
            b%pairs = b%pairs + 1.0_dp
        end if
        z(1:nx*ny) => zz
        f(1:nx*ny) => ff
        call aa%init(nx*ny, opts%anderson_memory)
        its = 0
        res_prev = 1.0_dp
        do
            ! x = resolvent of z; the inner heights M (2x - z)
            fft%x = zz
            call fft%forward()
            !$omp parallel do private(i)
            do j = 1, ny
                do i = 1, nq
                    b%hk(i, j) = fft%k(i, j)
                    fft%k(i, j) = am(i, j)*fft%k(i, j) + cm(i, j)
                    b%hk(i, j) = mn(i, j)*(2.0_dp*n*fft%k(i, j) - b%hk(i, j))
                end do
            end do
            !$omp end parallel do
            call fft%backward_unscaled()
            b%pairs = b%pairs + 1.0_dp
            x = fft%x

            ! y = the metric projection of 2x - z onto C
            itol = max(opts%tolerance/3.0_dp, inner_fraction*res_prev)
            call b%solve(fft, y, itol, opts%max_iterations, its, same_start=.true.)

            ! the residual of y on a fresh K y (from the transform of y the inner solve kept), in
            ! two fused passes with veslide_contact's measures; confirmed by problem%residuals
            fft%k = kn*b%pk
            call fft%backward_unscaled()
            b%pairs = b%pairs + 0.5_dp
            nc = 0; s1 = 0.0_dp
            !$omp parallel do private(i) reduction(+:nc, s1)
            do j = 1, ny
                do i = 1, nx
                    if (y(i, j) > 0.0_dp) then
                        nc = nc + 1; s1 = s1 + fft%x(i, j) - problem%hc(i, j)/hs
                    end if
                end do
            end do
            !$omp end parallel do
            d = -s1/max(nc, 1)
            gmin = huge(1.0_dp); spg = 0.0_dp; sp = 0.0_dp
            !$omp parallel do private(i, g) reduction(+:spg, sp) reduction(min:gmin)
            do j = 1, ny
                do i = 1, nx
                    g = fft%x(i, j) - problem%hc(i, j)/hs + d
                    gmin = min(gmin, g)
                    spg = spg + y(i, j)*g
                    sp = sp + y(i, j)
                end do
            end do
            !$omp end parallel do
            ! (y >= 0 by construction: the negative-pressure measure is 0)
            call residual_measures(state, hs*gmin, p_mean*hs*spg, p_mean*sp, 0.0_dp, p_mean*sp, n, p_mean, hs)
            if (state%residual <= opts%tolerance .or. its >= opts%max_iterations) then
                state%p = p_mean*y
                state%u = hs*fft%x
                call problem%residuals(state)
                if (state%residual <= opts%tolerance) then
                    state%converged = .true.; exit
                end if
                if (its >= opts%max_iterations) exit
            end if
            res_prev = state%residual

            ff = y - x

            accelerated = aa%step(z, f)
        end do
        state%iterations = its
        state%operator_applications = ceiling(b%pairs)

    contains

        !> The resolvent's multipliers for the step gamma: x^/N = am z^ + cm, cm = gamma h^/(M + gamma K)/N
        subroutine set_step()
            integer :: i, j
            do j = 1, ny
                do i = 1, nq
                    if (mn(i, j) > 0.0_dp) then
                        am(i, j) = mn(i, j)/(mn(i, j) + gamma*kn(i, j))/n
                        cm(i, j) = gamma*hk(i, j)/(mn(i, j) + gamma*kn(i, j))/(n*n)
                    else
                        am(i, j) = 1.0_dp/n; cm(i, j) = (0.0_dp, 0.0_dp)
                    end if
                end do
            end do
        end subroutine set_step

    end subroutine preconditioned_douglas_rachford

end module veslide_solver_pdr
