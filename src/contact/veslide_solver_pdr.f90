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
!>   z <- z + lambda (y - x), over-relaxed (lambda = 1.5; Eckstein & Bertsekas, Math. Program.
!>       55 (1992) 293: convergent for 0 < lambda < 2), or with `anderson_memory` > 0 the plain
!>       step accelerated by Anderson mixing (`anderson_t`; 12 + 8 m bytes per cell more).
!> At the fixed point x = y = p. The solver borrows the kernel's multiplier (no copy of it) and
!> returns it before it ends. The inner problems are solved to a tolerance that follows the
!> outer residual (0.3 of it, and never below a third of the target); every outer
!> iteration confirms the residual of y on a fresh K y. Measured in docs/solver-scaling.md.
!> Sums row by row and then over the rows in order (veslide_collective): the same path for any
!> number of threads or processes.
module veslide_solver_pdr
    use, intrinsic :: iso_c_binding, only: c_f_pointer, c_loc
    use, intrinsic :: iso_fortran_env, only: i8 => int64
    use veslide_kinds, only: dp
    use veslide_fftw, only: fft2d_t
    use veslide_contact, only: contact_problem_t, contact_state_t, residual_measures
    use veslide_solver_options, only: solver_options_t, progress_ticker_t
    use veslide_anderson, only: anderson_t
    use veslide_solver_bccg, only: bccg_t
    use veslide_collective, only: ordered_sum, global_min, global_count
    implicit none
    private
    public :: preconditioned_douglas_rachford

contains

    subroutine preconditioned_douglas_rachford(problem, fft, opts, state, gap0, cold)
        !> its kernel's multiplier is lent to the solve and returned unchanged
        type(contact_problem_t), intent(inout) :: problem
        type(fft2d_t), intent(inout) :: fft
        type(solver_options_t), intent(in) :: opts
        !> on entry the starting pressure (problem%start); on exit the solution
        type(contact_state_t), intent(inout) :: state
        !> gap of the starting pressure [m] (default: zero gap)
        real(dp), intent(in), optional :: gap0(:, :)
        !> the start is problem%start's uniform pressure (no warm start): begin from the solution
        !> in full contact instead when that is admissible
        logical, intent(in), optional :: cold
        real(dp), parameter :: inner_fraction = 0.3_dp    ! docs/solver-scaling.md (0.2 with Anderson)
        !> over-relaxation of the plain step (docs/solver-scaling.md: 1.5 against 1.7 and Anderson)
        real(dp), parameter :: relaxation = 1.5_dp
        type(bccg_t) :: b
        type(anderson_t) :: aa
        !> kd: the kernel's multiplier K_d (lent); K/N = s K_d in the units of the solve
        complex(dp), allocatable :: kd(:, :), cm(:, :)
        !> z and f (which holds x until y is known) live in the memory of the state's g and u,
        !> which the solve needs only to confirm a result; y is the state's p in units of p_mean
        real(dp), allocatable, target :: zz(:, :), ff(:, :)
        real(dp), pointer :: z(:), f(:)
        real(dp) :: hs, p_mean, gamma, n, s, gs, itol, res_prev, d, s1, gmin, spg, sp, g, t2(2)
        real(dp), allocatable :: rows(:, :)
        integer :: nx, ny, na, nb, its, i, j, sh(2)
        integer(i8) :: nc, cnt(1)
        logical :: accelerated, mixing
        type(progress_ticker_t) :: ticker

        nx = size(problem%h, 1); ny = size(problem%h, 2)
        sh = problem%kernel%grid%spectral_shape(); na = sh(1); nb = sh(2)
        n = problem%kernel%grid%cells()
        allocate (rows(2, ny))
        hs = problem%height_scale_m
        p_mean = problem%p_mean_pa
        state%method = 'pdr'
        call ticker%start(opts, 'pdr')
        gamma = opts%step
        if (.not. (gamma > 0.0_dp)) gamma = 1.0_dp
        mixing = opts%anderson_memory > 0

        ! multipliers: K/N = s K_d and M/N = |K|/N (held by the inner solver as b%ks),
        ! dimensionless; the resolvent's constant part cm
        call problem%kernel%lend_multiplier(kd)
        s = p_mean/(hs*n)
        gs = gamma*s
        call b%init(fft, s*abs(kd), problem%kernel%grid)
        fft%x = (problem%h - problem%h_mean)/hs
        call fft%forward()
        b%pairs = 0.5_dp
        call set_step()

        ! start: y = p, z = p + gamma M^-1 g (g the gap of the start, when given)
        state%p = state%p/p_mean
        call take_work_arrays()
        if (present(gap0)) then
            fft%x = gap0/hs
            call z_from_gap()
        else
            if (present(cold)) then
                if (cold) call start_from_full_contact()
            end if
            zz = state%p
        end if
        if (mixing) call aa%init(nx*ny, opts%anderson_memory, problem%kernel%grid)
        its = 0
        res_prev = 1.0_dp
        do
            ! x = resolvent of z; the inner heights M (2x - z)
            fft%x = zz
            call fft%forward()
            !$omp parallel do schedule(guided) private(i)
            do j = 1, nb
                do i = 1, na
                    b%hk(i, j) = fft%k(i, j)
                    if (b%ks(i, j) > 0.0_dp) then
                        fft%k(i, j) = b%ks(i, j)*fft%k(i, j)/((b%ks(i, j) + gs*kd(i, j))*n) + cm(i, j)
                    else
                        fft%k(i, j) = fft%k(i, j)/n
                    end if
                    b%hk(i, j) = b%ks(i, j)*(2.0_dp*n*fft%k(i, j) - b%hk(i, j))
                end do
            end do
            !$omp end parallel do
            call fft%backward_unscaled()
            b%pairs = b%pairs + 1.0_dp
            ff = fft%x                                    ! x

            ! y = the metric projection of 2x - z onto C
            itol = max(opts%tolerance/3.0_dp, inner_fraction*res_prev)
            call b%solve(fft, state%p, itol, opts%max_iterations, its, same_start=.true.)

            ! the residual of y on a fresh K y (from the transform of y the inner solve kept), in
            ! two fused passes with veslide_contact's measures; confirmed by problem%residuals
            fft%k = (s*kd)*b%pk
            call fft%backward_unscaled()
            b%pairs = b%pairs + 0.5_dp
            nc = 0
            !$omp parallel do schedule(guided) private(i, g) reduction(+:nc)
            do j = 1, ny
                g = 0.0_dp
                do i = 1, nx
                    if (state%p(i, j) > 0.0_dp) then
                        nc = nc + 1; g = g + (fft%x(i, j) - (problem%h(i, j) - problem%h_mean)/hs)
                    end if
                end do
                rows(1, j) = g
            end do
            !$omp end parallel do
            call ordered_sum(problem%kernel%grid, rows(1:1, :), t2(1:1))
            cnt(1) = nc; call global_count(problem%kernel%grid, cnt); nc = cnt(1)
            s1 = t2(1)
            d = -s1/real(max(nc, 1_i8), dp)
            gmin = huge(1.0_dp)
            !$omp parallel do schedule(guided) private(i, g, t2) reduction(min:gmin)
            do j = 1, ny
                t2 = 0.0_dp
                do i = 1, nx
                    g = fft%x(i, j) - (problem%h(i, j) - problem%h_mean)/hs + d
                    gmin = min(gmin, g)
                    t2(1) = t2(1) + state%p(i, j)*g
                    t2(2) = t2(2) + state%p(i, j)
                end do
                rows(:, j) = t2
            end do
            !$omp end parallel do
            call ordered_sum(problem%kernel%grid, rows, t2)
            call global_min(problem%kernel%grid, gmin)
            spg = t2(1); sp = t2(2)
            ! (y >= 0 by construction: the negative-pressure measure is 0)
            call residual_measures(state, hs*gmin, p_mean*hs*spg, p_mean*sp, 0.0_dp, p_mean*sp, n, p_mean, hs)
            if (state%residual <= opts%tolerance .or. its >= opts%max_iterations) then
                call give_back_work_arrays()
                state%p = p_mean*state%p
                state%u = hs*fft%x
                call problem%residuals(state)
                if (state%residual <= opts%tolerance) then
                    state%converged = .true.; exit
                end if
                if (its >= opts%max_iterations) exit
                ! not confirmed on the fresh residual (a result at the edge of the tolerance; z
                ! and x were given up to it): on from y and its gap, z = y + gamma M^-1 g
                state%p = state%p/p_mean
                fft%x = state%g/hs
                call take_work_arrays()
                call z_from_gap()
                if (mixing) call aa%reset()
                res_prev = state%residual
                cycle
            end if
            res_prev = state%residual
            call ticker%tick(its, state%residual, ceiling(b%pairs))

            if (mixing) then
                ff = state%p - ff                         ! f = y - x
                accelerated = aa%step(z, f)
            else
                !$omp parallel do schedule(guided) private(i)
                do j = 1, ny
                    do i = 1, nx
                        zz(i, j) = zz(i, j) + relaxation*(state%p(i, j) - ff(i, j))
                    end do
                end do
                !$omp end parallel do
            end if
        end do
        call problem%kernel%take_back_multiplier(kd)
        state%iterations = its
        state%operator_applications = ceiling(b%pairs)

    contains

        !> y = the solution in full contact, P = 1 + H/K (one inverse transform of h^, which fft%k
        !> holds), when it is admissible (P >= 0 everywhere): then it is the solution, confirmed by
        !> the first outer iteration. (Started from it clipped at zero when it is negative on up to
        !> half the cells, the hard cases near full contact took as many FFT pairs as from the
        !> uniform pressure: docs/solver-scaling.md.)
        subroutine start_from_full_contact()
            integer(i8) :: neg(1)
            where (b%ks > 0.0_dp)
                fft%k = fft%k/((n*n*s)*kd)
            elsewhere
                fft%k = (0.0_dp, 0.0_dp)
            end where
            call fft%backward_unscaled()
            b%pairs = b%pairs + 0.5_dp
            neg(1) = count(fft%x < -1.0_dp, kind=i8)
            call global_count(problem%kernel%grid, neg)
            if (neg(1) == 0) state%p = 1.0_dp + fft%x
        end subroutine start_from_full_contact

        !> z and f take the memory of the state's g and u (their values are not needed)
        subroutine take_work_arrays()
            call move_alloc(state%g, zz); call move_alloc(state%u, ff)
            z(1:nx*ny) => zz
            f(1:nx*ny) => ff
        end subroutine take_work_arrays

        subroutine give_back_work_arrays()
            nullify (z, f)
            call move_alloc(zz, state%g); call move_alloc(ff, state%u)
        end subroutine give_back_work_arrays

        !> z = y + gamma M^-1 g from the gap g/h_s in fft%x (one FFT pair)
        subroutine z_from_gap()
            call fft%forward()
            where (b%ks > 0.0_dp)
                fft%k = fft%k*(gamma/(b%ks*n*n))
            elsewhere
                fft%k = (0.0_dp, 0.0_dp)
            end where
            call fft%backward_unscaled()
            zz = state%p + fft%x
            b%pairs = b%pairs + 1.0_dp
        end subroutine z_from_gap

        !> The resolvent for the step gamma: x^/N = M z^/((M + gamma K) N) + cm, with the constant
        !> part cm = gamma h^/(M + gamma K)/N^2 from h^ in fft%k (x^/N = z^/N on the mean mode)
        subroutine set_step()
            integer :: i, j
            allocate (cm(na, nb))
            do j = 1, nb
                do i = 1, na
                    if (b%ks(i, j) > 0.0_dp) then
                        cm(i, j) = gamma*fft%k(i, j)/(b%ks(i, j) + gs*kd(i, j))/(n*n)
                    else
                        cm(i, j) = (0.0_dp, 0.0_dp)
                    end if
                end do
            end do
        end subroutine set_step

    end subroutine preconditioned_douglas_rachford

end module veslide_solver_pdr
