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
!>       step accelerated by Anderson mixing (`anderson_t`; 16 + 8 m bytes per cell more).
!> On the device x is kept in u, as on the CPU (the same arithmetic), and cuFFT has a work area of
!> its own (8 bytes per cell), where the device has room for it; where it has not (or with
!> `opts%device_lean`), the lean layout: the relaxation in two parts, z - lambda x before the
!> inner solve and + lambda y after it (the same step to round-off, not bit for bit: the path can
!> take an iteration more or fewer), so that x is not kept across the inner solve and u lends
!> cuFFT its work area (veslide_solver_table: 8 bytes per cell fewer). With mixing, which keeps
!> f = y - x in u, the transform always has its own.
!> At the fixed point x = y = p. The solver works on the kernel's multiplier where the solve
!> runs (a view on the host: no copy of it). The inner problems are solved to a tolerance that follows the
!> outer residual (0.3 of it, and never below a third of the target); every outer
!> iteration confirms the residual of y on a fresh K y. Measured in docs/solver-scaling.md.
!> Sums row by row and then over the rows in order (veslide_collective): the same path for any
!> number of threads or processes. Its projection is BCCG's, an active-set method for the hard
!> wall: pdr takes that contact law only (veslide_solver_table).
module veslide_solver_pdr
    use, intrinsic :: iso_fortran_env, only: i8 => int64
    use veslide_kinds, only: dp
    use veslide_contact, only: contact_problem_t, contact_state_t, contact_fields_t, residual_measures
    use veslide_solver_options, only: solver_options_t, progress_ticker_t
    use veslide_anderson, only: anderson_t
    use veslide_solver_bccg, only: bccg_t
    use veslide_collective, only: ordered_sum, global_min, global_count
    use veslide_arrays, only: carray_t
    use veslide_passes, only: divide, scale, scaled_copy, divided_copy, centre_divide, count_below
    use veslide_bccg_passes, only: metric
    use veslide_pdr_passes, only: step_constant, resolvent, scaled_product, residual_sums, residual_gap, relax, &
                                  add_scaled, &
                                  full_contact, gap_to_z, sum_of, one_plus, difference_from
    use veslide_device, only: device_failed, device_has_room
    implicit none
    private
    public :: preconditioned_douglas_rachford

contains

    !> The splitting on the fields `f` (host or device)
    subroutine preconditioned_douglas_rachford(problem, f, opts, state, gap0, cold)
        type(contact_problem_t), intent(in) :: problem
        type(contact_fields_t), intent(inout), target :: f
        type(solver_options_t), intent(in) :: opts
        !> on entry the starting pressure (problem%start, in f%p); on exit the solution
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
        !> the resolvent's constant part
        type(carray_t) :: cm
        ! z and f (which holds x until y is known) live in the state's g and u (f%g, f%u), which
        ! the solve needs only to confirm a result; y is the state's p (f%p) in units of p_mean
        real(dp) :: hs, p_mean, gamma, n, s, gs, itol, res_prev, d, s1, gmin, spg, sp, t2(2)
        real(dp), allocatable :: rows(:, :)
        integer :: its, sh(2)
        integer(i8) :: nc, cnt(1)
        logical :: accelerated, mixing, two_part
        type(progress_ticker_t) :: ticker

        sh = problem%kernel%grid%spectral_shape()
        n = problem%kernel%grid%cells()
        allocate (rows(2, f%p%n2))
        hs = problem%height_scale_m
        p_mean = problem%p_mean_pa
        state%method = 'pdr'
        call ticker%start(opts, 'pdr')
        gamma = opts%step
        if (.not. (gamma > 0.0_dp)) gamma = 1.0_dp
        mixing = opts%anderson_memory > 0
        ! on the device: cuFFT's own work area where there is room (u keeps x), else the lean
        ! layout (the relaxation in two parts; u lends the work area)
        two_part = .false.
        if (f%device) then
            two_part = .not. mixing .and. (opts%device_lean .or. .not. device_has_room(f%t%work_bytes))
            if (.not. two_part) call f%t%lend_work()
        end if

        ! multipliers: K/N = s K_d and M/N = |K|/N (held by the inner solver as b%ks),
        ! dimensionless; the resolvent's constant part cm
        s = p_mean/(hs*n)
        gs = gamma*s
        call b%init(f%t, problem%kernel%grid)
        call metric(b%ks, f%kd, s, modulus=.true.)
        call centre_divide(f%t%x, f%h, problem%h_mean, hs)
        call f%t%forward()
        b%pairs = 0.5_dp
        call cm%create(sh(1), sh(2), f%device)
        call step_constant(cm, f%t%k, b%ks, f%kd, gamma, gs, n)

        ! start: y = p, z = p + gamma M^-1 g (g the gap of the start, when given)
        call divide(f%p, p_mean)
        if (present(gap0)) then
            if (f%gap_held) then
                call f%t%x%assign(f%g)                ! gap0, kept on the device from a study's last case
            else
                call f%t%x%upload(gap0)
            end if
            call divide(f%t%x, hs)
            call z_from_gap()
        else
            if (present(cold)) then
                if (cold) call start_from_full_contact()
            end if
            call f%g%assign(f%p)
        end if
        if (mixing) call aa%init(f%p%n1, f%p%n2, opts%anderson_memory, f%device, problem%kernel%grid)
        its = 0
        res_prev = 1.0_dp
        do
            ! x = resolvent of z; the inner heights M (2x - z)
            call f%t%x%assign(f%g)
            call f%t%forward()
            call resolvent(f%t%k, b%hk, b%ks, f%kd, cm, gs, n)
            call f%t%backward_unscaled()
            b%pairs = b%pairs + 1.0_dp
            if (two_part) then
                call add_scaled(f%g, f%t%x, -relaxation)  ! z - lambda x
            else
                call f%u%assign(f%t%x)                    ! x
            end if

            ! y = the metric projection of 2x - z onto C
            itol = max(opts%tolerance/3.0_dp, inner_fraction*res_prev)
            call b%solve(f%t, f%p, itol, opts%max_iterations, its, same_start=.true.)

            ! the residual of y on a fresh K y (from the transform of y the inner solve kept), in
            ! two fused passes with veslide_contact's measures; confirmed by problem%residuals_on
            call scaled_product(f%t%k, f%kd, b%pk, s)
            call f%t%backward_unscaled()
            b%pairs = b%pairs + 0.5_dp
            call residual_sums(f%t%x, f%h, problem%h_mean, hs, f%p, rows(1, :), nc)
            call ordered_sum(problem%kernel%grid, rows(1:1, :), t2(1:1))
            cnt(1) = nc; call global_count(problem%kernel%grid, cnt); nc = cnt(1)
            s1 = t2(1)
            d = -s1/real(max(nc, 1_i8), dp)
            call residual_gap(f%t%x, f%h, problem%h_mean, hs, d, f%p, rows, gmin)
            call ordered_sum(problem%kernel%grid, rows, t2)
            call global_min(problem%kernel%grid, gmin)
            spg = t2(1); sp = t2(2)
            ! (y >= 0 by construction: the negative-pressure measure is 0)
            call residual_measures(problem%law, state, hs*gmin, p_mean*hs*spg, p_mean*sp, 0.0_dp, p_mean*sp, n, &
                                   p_mean, hs)
            if (f%device) then
                if (device_failed()) exit
            end if
            if (state%residual <= opts%tolerance .or. its >= opts%max_iterations) then
                call scale(f%p, p_mean)
                call scaled_copy(f%u, f%t%x, hs)
                call problem%residuals_on(f, state)
                if (state%residual <= opts%tolerance) then
                    state%converged = .true.; exit
                end if
                if (its >= opts%max_iterations) exit
                ! not confirmed on the fresh residual (a result at the edge of the tolerance; z
                ! and x were given up to it): on from y and its gap, z = y + gamma M^-1 g
                call divide(f%p, p_mean)
                call divided_copy(f%t%x, f%g, hs)
                call z_from_gap()
                if (mixing) call aa%reset()
                res_prev = state%residual
                cycle
            end if
            res_prev = state%residual
            call ticker%tick(its, state%residual, ceiling(b%pairs))

            if (mixing) then
                call difference_from(f%u, f%p)            ! f = y - x
                accelerated = aa%step(f%g, f%u)
            else if (two_part) then
                call add_scaled(f%g, f%p, relaxation)     ! (z - lambda x) + lambda y
            else
                call relax(f%g, f%p, f%u, relaxation)
            end if
        end do
        state%iterations = its
        state%operator_applications = ceiling(b%pairs)
        call b%destroy(); call cm%destroy(); call aa%destroy()

    contains

        !> y = the solution in full contact, P = 1 + H/K (one inverse transform of h^, which t%k
        !> holds), when it is admissible (P >= 0 everywhere, the hard wall's bound: pdr takes that
        !> law only, veslide_solver_table): then it is the solution, confirmed by
        !> the first outer iteration. (Started from it clipped at zero when it is negative on up to
        !> half the cells, the hard cases near full contact took as many FFT pairs as from the
        !> uniform pressure: docs/solver-scaling.md.)
        subroutine start_from_full_contact()
            integer(i8) :: neg(1)
            call full_contact(f%t%k, b%ks, f%kd, n*n*s)
            call f%t%backward_unscaled()
            b%pairs = b%pairs + 0.5_dp
            neg(1) = count_below(f%t%x, -1.0_dp)
            call global_count(problem%kernel%grid, neg)
            if (neg(1) == 0) call one_plus(f%p, f%t%x)
        end subroutine start_from_full_contact

        !> z = y + gamma M^-1 g from the gap g/h_s in t%x (one FFT pair)
        subroutine z_from_gap()
            call f%t%forward()
            call gap_to_z(f%t%k, b%ks, gamma, n)
            call f%t%backward_unscaled()
            call sum_of(f%g, f%p, f%t%x)
            b%pairs = b%pairs + 1.0_dp
        end subroutine z_from_gap

    end subroutine preconditioned_douglas_rachford

end module veslide_solver_pdr
