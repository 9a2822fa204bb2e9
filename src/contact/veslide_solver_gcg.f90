!> Conjugate gradients on the gap ('gcg'), for the adhesive contact laws: on a symmetric operator
!> (an elastic solid, or a viscoelastic one at rest) directly, on a non-symmetric one (a
!> viscoelastic solid in motion, an interfacial shear) inside a Douglas-Rachford splitting.
!>
!> With an adhesive law (veslide_contact_law) the traction is p = p_rep - sigma(g): the repulsive
!> pressure of the hard wall (p_rep >= 0, g >= 0, p_rep g = 0) less an attraction sigma(g) that
!> depends on the gap alone. No pressure-based method applies: p does not tell contact from
!> attraction, and the law is not monotone (sigma falls as the gap opens). In the gap it is an
!> energy: with A = K^-1 (the modulus multiplier, zero on the mean mode), u = g + h - d and
!> p = p_mean + A (g + h), the total energy
!>   Pi(g) = 1/2 <g + h, A (g + h)> + sum V(g) + p_mean sum g,     V' = sigma, V(inf) = 0,
!> has the gradient p + sigma(g) = p_rep, so the solution is a local minimum of Pi over g >= 0
!> (zero gradient where the gap is open, a non-negative one where it is closed): the same
!> discrete problem Tamaas's PolonskyKeerRey solves on the gap with an adhesion functional (Rey,
!> Anciaux, Molinari, Comput. Mech. 60 (2017) 69), and so is this method: Polonsky and Keer's
!> constrained conjugate gradients with the gap as the primal variable.
!>
!> Inner solve, at a fixed mean gap d (the approach; its Lagrange multiplier is -p_mean):
!>   r = A (g + h) + sigma(g), the gradient; the free set: open cells (g > 0), and closed cells
!>       whose gradient less its mean over the open cells is negative (they pull away);
!>   lambda = mean of r over the free set, r <- r - lambda (so p_mean = -lambda);
!>   z = P r on the free set (0 elsewhere; its mean over the set removed where the mean gap is
!>   held), P the preconditioner 1/(A + k) (k the law's steepest slope) where
!>   choose_preconditioner takes it, else z = r;
!>   t = z + delta (<r, z>/<r_prev, z_prev>) t on the free set (0 elsewhere), the step
!>   tau = <r, t>/<t, A t> (A's curvature alone, as Polonsky and Keer and Rey et al.: that of V
!>   is negative and would stall the step where the law is steepest), g <- max(g - tau t, 0)
!>   with delta = 0 after a step that closed a cell (the conjugacy restarts; also where
!>   <r, z> <= 0, which a preconditioned direction never gives in exact arithmetic; in the
!>   splitting's inner solves not after a step that closed only a few cells, few_clipped), and
!>   the open cells shifted to keep the mean gap d.
!> Converged when max |r| over the open cells and max(-r) over the closed ones are below the
!> tolerance (in units of the pressure scale). An iteration costs the FFT pair of A t, one more
!> for P where it is taken, and one for A (g + h) afresh after a step that clipped or shifted a
!> cell (otherwise A (g + h) is carried along the step, and formed afresh every 50 iterations
!> and before the solve ends).
!> Approach control (problem%approach_control): one inner solve at the given mean gap, the load
!> its result. Load control (the case's `&load mean_pressure_pa`, which may be tensile): the mean gap is
!> found by the secant method on p_mean(d), decreasing in d on every branch stable under load
!> control, each inner solve warm-started from the last; a load beyond the pull-off force has no
!> solution (the gap opens without bound), reported as not converged. (The secant's slope is
!> updated from points whose loads differ by more than 100 times the inner tolerance while the
!> load is unbracketed, 10 times once bracketed.)
!> Where more than one solution exists at one load (JKR: a contact and no contact; a partial and
!> a full one), the method returns the one its start leads to: a warm start from the last load
!> of a sweep follows its branch (a start in full contact stays there while the law admits it);
!> a cold start begins in contact at the highest point.
!>
!> A non-symmetric operator (A = 1/K complex, Re A > 0 for a passive solid) has no energy: the
!> problem is the inclusion 0 in T(g) + dPsi(g) with T(g) = A (g + h) monotone and Psi the law's
!> energy sum V(g) with g >= 0 and the mean gap held (weakly convex, not convex). Douglas-Rachford
!> in the metric M = |A| (as `pdr` does in the pressure for the hard wall), with step gamma:
!>   x = (I + gamma M^-1 T)^-1 z:  x^ + h^ = (z^ + h^)/(1 + gamma A/M)   (one FFT pair; with
!>       M = |A| and gamma = 1 the denominator's modulus is 2 cos(delta/2) >= sqrt 2, delta the
!>       loss angle)
!>   y = argmin over g >= 0 at the mean gap of 1/2 <y - v, (M/gamma) (y - v)> + sum V(y),
!>       v = 2x - z: the symmetric adhesive problem above with the multiplier M/gamma and the
!>       heights -v, solved by the conjugate gradients warm-started from the last y
!>   z <- z + lambda (y - x), over-relaxed (lambda = `relaxation`, 1.5, as pdr's; Eckstein and
!>       Bertsekas, Math. Program. 55 (1992) 293)
!> At a fixed point x = y solves the problem. Each outer iteration measures the residual of y on
!> the operator itself (one FFT pair) and asks the inner solve for 0.3 of it, never below a
!> hundredth of the outer tolerance, in at most `inner_steps` (5) conjugate-gradient steps: an
!> inexact splitting, whose inner solves, warm-started, refine y as z settles instead of solving
!> to the letter a problem the next z changes. Where that is too inexact for the outer iteration
!> (its residual not down by `progress`, a factor 5, over `patience`, 10, outer iterations: a
!> hard-wall-like contact forming under a stiff operator, whose inner solves take thousands of
!> steps), the bound doubles, up to unbounded. Measured in docs/adhesion.md (the paper scene:
!> 1144 -> 707 FFT pairs at 256^2, 2613 -> 1388 at 2048^2). Where even that makes no progress
!> (`rescue_after` doublings in a row: a contact near full cycled between contact sets), the
!> inner problem is likely not convex, M softer than the law's steepest slope k on the long
!> waves: the metric is floored (M' = max(M, gamma k), the mean mode as it was), which makes it
!> convex and its solution unique, and the splitting restarts from y (once; it costs speed on
!> the modes it changes, so it is not the default). gamma = 1 (the options' step when
!> set), as measured on the sliding JKR wave (docs/adhesion.md): 0.6 is slower and 1.5 or 3
!> diverge (a splitting of a non-convex problem converges for steps small against the law's
!> curvature).
!> Under load control the metric takes the mean mode too (at the softest mode's stiffness) and
!> the load is T's constant part (T(g) = A (g + h) + p_mean): one loop, no secant, the inner
!> solves free of the mean gap; under approach control they hold it. A sparse contact is far
!> softer than that mode, and its mean gap then converges slowly: where it does, the mean's
!> metric is retuned once to the contact's stiffness read from that rate, and restored for the
!> last digits (retune_mean; docs/adhesion.md: 0.48 to 1.07 times the FFT pairs over 90 scenes,
!> 0.79 in all). The start
!> z = y + gamma M^-1 A (y + h) is the fixed point's z where y is the solution (a warm start).
!> Every pass over the grid is a named procedure with a CPU twin and a CUDA twin
!> (veslide_gcg_passes), so the solve runs where its fields are: on the host, or on the device
!> (veslide_solver_table), the control flow here either way. Sums row by row and then over the
!> rows in order (veslide_collective): the same path for any number of threads or processes.
module veslide_solver_gcg
    use, intrinsic :: iso_c_binding, only: c_int
    use veslide_kinds, only: dp
    use veslide_contact, only: contact_problem_t, contact_state_t, contact_fields_t
    use veslide_contact_law, only: ADH_STRESS, ADH_RANGE, LAW_EXPONENTIAL, LAW_DUGDALE
    use veslide_solver_options, only: solver_options_t, progress_ticker_t
    use veslide_collective, only: ordered_sum, ordered_sum_scalar, global_max, global_min, global_any
    use veslide_arrays, only: rarray_t, carray_t, iarray_t
    use veslide_device, only: device_failed
    use veslide_passes, only: fill, subtract, scaled_copy, centre_divide, row_sums
    use veslide_gcg_passes, only: gcg_attract, gcg_free_set, gcg_centre, gcg_spectral, gcg_mask, gcg_dot, &
                                  gcg_shift_dot, gcg_direction, gcg_curvature, gcg_step, gcg_gap_sums, gcg_shift_open, &
                                  gcg_combine, gcg_extremes, SPECTRAL_A, SPECTRAL_K, SPECTRAL_OPERATOR, &
                                  SPECTRAL_RESOLVENT, SPECTRAL_START, COMBINE_SUM, COMBINE_DIFFERENCE, &
                                  COMBINE_REFLECT, COMBINE_ACCUMULATE, COMBINE_PRESSURE, COMBINE_DISPLACEMENT, &
                                  COMBINE_FROM, COMBINE_AXPY
    implicit none
    private
    public :: gap_conjugate_gradients

    !> the secant's most steps on the mean gap (load control)
    integer, parameter :: max_outer = 60
    !> the inner solves' tolerance while the load is off: this fraction of its error (the
    !> secant needs p_mean(d) no closer than that; the last solve is to the tolerance)
    real(dp), parameter :: inexact = 1.0e-2_dp
    !> the most solves a tenth tighter when the problem's residual is above the tolerance
    integer, parameter :: max_tighten = 4
    !> the splitting, or an inner solve within it, has stalled at its round-off when its
    !> gradient has not fallen below 0.9 of its best for `stall_outer` outer or `stall_inner`
    !> inner iterations while that best is within `stall_band` times the estimated floor
    !> (round_off_floor, an estimate that can be far above the real one: on a profile whose rows
    !> are equal, the modes across them carry no round-off); it then stops there, and the
    !> problem's residual gives the verdict. Not on a symmetric operator: there the thin bonded
    !> layers' slow conjugate gradients plateau within that band and fall on (docs/adhesion.md)
    integer, parameter :: stall_inner = 100, stall_outer = 20
    real(dp), parameter :: stall_band = 16.0_dp
    !> the inner solves are preconditioned when the law's steepest slope is at most this
    !> fraction of the operator's largest stiffness (docs/adhesion.md: measured crossover)
    real(dp), parameter :: stiff_law = 0.05_dp
    !> the splitting's over-relaxation (docs/adhesion.md: 1.5 against 1 to 1.9)
    real(dp), parameter :: relaxation = 1.5_dp
    !> the splitting's inner solves: at most `inner_steps` steps each, a bound that doubles when
    !> the outer residual has not fallen below `progress` times itself over `patience` outer
    !> iterations (docs/adhesion.md: 5 steps against 2 to 8; a bound of 5 that never doubles left
    !> a contact forming under Einf/E0 = 1000 unconverged)
    integer, parameter :: inner_steps = 5, patience = 10
    real(dp), parameter :: progress = 0.2_dp
    !> after this many doublings of that bound in a row (40 outer iterations without the progress),
    !> the splitting's metric is floored at the law's steepest slope and the splitting restarted
    !> from y, once (floor_metric; docs/adhesion.md: a contact near full that cycled)
    integer, parameter :: rescue_after = 4
    !> the mean mode's metric under load control (retune_mean; docs/adhesion.md): the mean gap
    !> is read every `mean_window` outer iterations; where three readings say it converges at
    !> `slow_mean` or slower an outer iteration, the metric is retuned to the contact's
    !> stiffness, at least `least_mean` of the softest mode's (a tenth: the one estimate of 0.023
    !> stalled a solve at 3e-10), and restored once the residual is below `restore_below`
    integer, parameter :: mean_window = 3
    real(dp), parameter :: slow_mean = 0.6_dp, least_mean = 0.1_dp, restore_below = 1.0e-4_dp
    !> the splitting's inner solves keep the conjugacy through a step that clipped (closed) at most
    !> `few_clipped` cells and at most `few_share` of the free ones; more restart it, as every clip
    !> does on a symmetric operator (docs/adhesion.md: the edge cells of a rough contact, whose gap
    !> at the solution is a hair above 0, open and close for tens of outer iterations, and each
    !> restart cost the other cells their conjugacy; 8 against 2 to 32. The share leaves grids of
    !> fewer than 10^4 cells as they were: on profiles a clipped cell is a contact's edge, and
    !> keeping the conjugacy there cost up to 4 times the FFT pairs)
    real(dp), parameter :: few_clipped = 8.0_dp, few_share = 1.0e-4_dp

contains

    !> The adhesive problem on the fields `f`, on the host or on the device (solution: p in f%p,
    !> the gap in f%g with its closed cells exactly 0, u = K p in f%u, the approach in
    !> state%approach_m)
    subroutine gap_conjugate_gradients(problem, f, opts, state, gap0)
        type(contact_problem_t), intent(in), target :: problem
        type(contact_fields_t), intent(inout) :: f
        type(solver_options_t), intent(in) :: opts
        type(contact_state_t), intent(inout) :: state
        !> gap of the start [m] (a warm start); default: in contact at the highest point
        real(dp), intent(in), optional :: gap0(:, :)
        !> the heights (the inner solves' in the splitting), the gap, the search direction, A (g + h)
        type(rarray_t) :: hn, g, t, r
        !> the gradient, and its preconditioned form (then A t)
        type(rarray_t), target :: at, pz
        !> the free set, and the cells at Dugdale's zone edge (int8 sets)
        type(iarray_t) :: free, edge
        ! the splitting's (a non-symmetric operator): its z and x, the heights
        type(rarray_t) :: z, x, h0
        !> the modulus multiplier A = 1/K (real; with the splitting the metric over the step, |1/K|/gamma
        !> or floor_metric's) and, with the splitting, 1/K itself, on the half-spectrum where the
        !> solve runs; `ainv` and `kinv` their host copies, from which the preconditioner is chosen
        type(rarray_t) :: a_s
        type(carray_t) :: k_s
        real(dp), allocatable, target :: ainv(:, :)
        complex(dp), allocatable, target :: kinv(:, :)
        !> the kernel's multiplier K_d on the host (the kernel's own, where the solve runs)
        type(carray_t) :: kd
        real(dp), allocatable :: gstart(:, :)
        real(dp) :: hs, ps, cells, target, s0, rho, d, p_d, slope, tol, gamma, softest, mean_metric, least, most
        !> the estimated round-off floor of the gradient's largest entry (see round_off_floor),
        !> and `reached` the level where a solve's gradient stalled within `stall_band` of it
        !> (at_floor; 0 before): no later inner solve is asked for less than the lower of the two
        real(dp) :: floor_tol, reached
        logical :: at_floor
        integer :: nx, ny, its, kind, attempt
        !> the splitting (a non-symmetric operator); the inner solves hold the mean gap (all but
        !> the splitting's under load control, whose metric holds the mean instead)
        logical :: ok, tight, split, hold_mean, dev
        !> the inner solves' preconditioner 1/(A + law_stiffness) (`preconditioned`: see
        !> choose_preconditioner)
        real(dp) :: law_stiffness
        logical :: preconditioned
        !> the splitting's bound on the steps of an inner solve (see inner_steps)
        integer :: inner_cap
        !> the splitting's metric has been floored at the law's stiffness (see floor_metric)
        logical :: floored
        !> the splitting's inner steps that kept the conjugacy through a few clipped cells
        integer :: n_kept
        !> the mean mode's metric was retuned (retune_mean), and restored to `m_first`
        logical :: retuned, restored
        real(dp) :: m_first
        type(progress_ticker_t) :: ticker

        nx = f%p%n1; ny = f%p%n2
        dev = f%device
        hs = problem%height_scale_m
        ps = problem%p_scale_pa
        cells = problem%kernel%grid%cells()
        target = problem%p_mean_pa/ps
        kind = problem%law%kind
        s0 = problem%law%param(ADH_STRESS)/ps
        rho = problem%law%param(ADH_RANGE)/hs
        split = .not. problem%kernel%symmetric
        state%method = 'gcg'
        call ticker%start(opts, 'gcg')
        call hn%create(nx, ny, dev); call g%create(nx, ny, dev); call t%create(nx, ny, dev)
        call r%create(nx, ny, dev); call at%create(nx, ny, dev); call pz%create(nx, ny, dev)
        call free%create(nx, ny, dev); call edge%create(nx, ny, dev)
        call centre_divide(hn, f%h, problem%h_mean, hs)
        ! the modulus multiplier A = 1/K (zero where K is: the mean mode), in units p_s/h_s per
        ! cell count (FFTW's unscaled pair); with the splitting the inner solves' M/gamma (formed
        ! on the host, from the kernel's multiplier there: a view, not a copy)
        call problem%kernel%multiplier_array(kd, .false.)
        if (split) then
            kinv = kd%h
            where (kinv /= (0.0_dp, 0.0_dp))
                kinv = hs/(ps*kinv*cells)
            end where
            ainv = abs(kinv)
            gamma = opts%step
            if (.not. (gamma > 0.0_dp)) gamma = 1.0_dp
            call z%create(nx, ny, dev); call x%create(nx, ny, dev); call h0%create(nx, ny, dev)
            call h0%assign(hn)
        else
            ainv = real(kd%h, dp)
            where (ainv /= 0.0_dp)
                ainv = hs/(ps*ainv*cells)
            end where
        end if
        call kd%destroy()
        floor_tol = round_off_floor()
        reached = 0.0_dp; at_floor = .false.; floored = .false.; retuned = .false.; restored = .false.
        n_kept = 0
        softest = lowest_compliance()
        hold_mean = .true.
        if (split) then
            ! under load control the metric takes the mean mode too, at the softest mode's
            ! stiffness (docs/adhesion.md): the load enters the splitting's operator
            hold_mean = problem%approach_control
            mean_metric = 1.0_dp/softest
            if (.not. hold_mean) then
                where (kinv == (0.0_dp, 0.0_dp)) ainv = mean_metric/cells
            end if
            ainv = ainv/gamma
        end if
        call choose_preconditioner()
        ! the multipliers where the solve runs (on the host views of these)
        if (dev) then
            ! (ainv kept on the host, 4 bytes per cell: floor_metric forms the floored metric there)
            call a_s%create(size(ainv, 1), size(ainv, 2), .true.); call a_s%upload(ainv)
            if (split) then
                call k_s%create(size(kinv, 1), size(kinv, 2), .true.); call k_s%upload(kinv)
                deallocate (kinv)
            end if
        else
            call a_s%view(ainv)
            if (split) call k_s%view(kinv)
        end if
        if (present(gap0)) then
            gstart = max(gap0/hs, 0.0_dp)
            if (dev) then
                call g%upload(gstart)
            else
                g%h = gstart
            end if
            deallocate (gstart)
        else
            call gcg_extremes(hn, least, most)
            d = most; call global_max(problem%kernel%grid, d)
            call gcg_combine(COMBINE_FROM, g, hn, hn, d)
        end if
        its = 0
        slope = 0.0_dp
        ! to the tolerance on the law's gradient; then confirmed on the problem's residual (a
        ! fresh K p), and solved again a tenth tighter while that is above the tolerance
        tol = opts%tolerance
        do attempt = 1, max_tighten
            if (split) call start_splitting()
            if (problem%approach_control) then
                ! the mean gap given, the load its result
                d = problem%mean_gap_m/hs
                call solve_at(d, p_d, ok, tol)
                target = p_d
            else if (split) then
                call splitting(d, p_d, ok, tol)
            else
                call carry_load()
            end if
            ! the solution in SI: p = p_mean + A (g + h) (in r), the gap, u = g + h - d
            if (split) call hn%assign(h0)
            call gcg_combine(COMBINE_PRESSURE, f%p, r, r, ps*p_d, ps, sum_mean_removed())
            call scaled_copy(f%g, g, hs)
            call gcg_combine(COMBINE_DISPLACEMENT, f%u, g, hn, d, hs)
            state%approach_m = hs*d
            state%iterations = its
            if (.not. (ok .and. tight .and. abs(p_d - target) <= tol)) then
                state%converged = .false.; exit
            end if
            call problem%confirm(f, state, opts%tolerance)
            if (state%converged) exit
            if (dev .and. device_failed()) exit
            call scaled_copy(f%g, g, hs)
            ! (stalled at the round-off, a tighter solve is the same solve)
            if (at_floor) exit
            tol = tol/10
        end do
        state%round_off = reached
        state%mean_metric_retuned = retuned
        state%kept_conjugacy_steps = n_kept
        call hn%destroy(); call g%destroy(); call t%destroy(); call r%destroy(); call at%destroy(); call pz%destroy()
        call free%destroy(); call edge%destroy(); call a_s%destroy(); call k_s%destroy()
        if (split) then
            call z%destroy(); call x%destroy(); call h0%destroy()
        end if

    contains

        !> The secant on p_mean(d) = target from the current g, bracketed once the sign changes
        !> (regula falsi); the inner solves to a fraction of the load's error, the last to `tol`
        subroutine carry_load()
            real(dp) :: d_prev, p_prev, d_new, lo(2), hi(2), itol
            logical :: have_lo, have_hi
            integer :: k
            d = total(g)/cells
            ! a start in full contact (a warm start from a load path's last case) stays there
            ! while the law admits it at the target: closed everywhere, the load is the closed
            ! gap's multiplier, so any load down to the one that pulls the trough open is carried
            ! (without this the secant opens the gap at the first tensile load: another branch)
            if (d <= 0.0_dp) then
                if (full_contact()) return
            end if
            call solve_at(d, p_d, ok, tol)
            if (.not. ok) return
            have_lo = .false.; have_hi = .false.
            do k = 1, max_outer
                if (abs(p_d - target) <= tol .and. tight) exit
                ! brackets: lo has p above the target (a gap too small), hi below
                if (p_d > target) then
                    lo = [d, p_d]; have_lo = .true.
                else
                    hi = [d, p_d]; have_hi = .true.
                end if
                if (slope < 0.0_dp) then
                    d_new = d + (target - p_d)/slope
                else
                    ! first step: the mean gap the difference would open over the lowest mode's
                    ! stiffness (a bound on the contact's), signed by the load
                    d_new = d + sign(max(0.05_dp, abs(p_d - target)*softest), p_d - target)
                end if
                if (have_lo .and. have_hi) then
                    if (.not. (d_new > lo(1) .and. d_new < hi(1))) d_new = lo(1) + (hi(1) - lo(1))* &
                        (lo(2) - target)/(lo(2) - hi(2))
                else
                    ! a load the open contact cannot carry: full contact (g = 0, p = p_mean + A h)
                    ! where that is the law's (p_rep >= 0 everywhere), the jump into it
                    if (d_new <= 0.0_dp) then
                        if (full_contact()) return
                    end if
                    ! unbracketed: the gap at most halved or doubled a step (p_mean(d) is far from
                    ! linear where contact spreads or opens)
                    d_new = min(max(d_new, 0.5_dp*d), 2.0_dp*d + 1.0_dp)
                end if
                d_prev = d; p_prev = p_d
                d = d_new
                ! (a tenth of the tolerance near the load: the mean pressure is as accurate as
                ! the gradient, and a secant through points closer than that sees only noise)
                itol = max(0.1_dp*tol, inexact*abs(p_d - target))
                call solve_at(d, p_d, ok, itol)
                if (.not. ok) return
                ! (the slope from points whose loads differ by more than their errors: 100 times
                ! the inner tolerance while the load is unbracketed, where a slope too shallow
                ! would step into full contact; 10 times once bracketed, where a slope frozen
                ! early made the last steps converge linearly, about 6 times a step)
                if (d /= d_prev .and. abs(p_d - p_prev) > merge(10, 100, have_lo .and. have_hi)*itol) &
                    slope = (p_d - p_prev)/(d - d_prev)
            end do
        end subroutine carry_load

        !> The solution in full contact at the target load, when the law admits it (the repulsive
        !> pressure p_mean + A h + sigma(0) nowhere negative): then g = 0, d = 0 and r = A h
        logical function full_contact() result(yes)
            real(dp) :: rmin, rmax
            call t%assign(g)                          ! (t: free between inner solves)
            call fill(g, 0.0_dp)
            call apply_operator(g, r)
            state%operator_applications = state%operator_applications + 1
            ! (min(r - m) is min(r) - m: rounding is monotone)
            call gcg_extremes(r, rmin, rmax)
            call global_min(problem%kernel%grid, rmin)
            yes = (rmin - sum_mean_removed()) + target + s0 >= 0.0_dp
            if (yes) then
                d = 0.0_dp; p_d = target; ok = .true.; tight = .true.
            else
                call g%assign(t)
            end if
        end function full_contact

        !> The problem at mean gap `dbar` to the tolerance `itol` (g updated, r = A (g + h) on
        !> exit, `pm` the mean pressure): the conjugate gradients on a symmetric operator, the
        !> splitting around them on another
        subroutine solve_at(dbar, pm, ok, itol)
            real(dp), intent(in) :: dbar, itol
            real(dp), intent(out) :: pm
            logical, intent(out) :: ok
            real(dp) :: d_held
            if (split) then
                d_held = dbar
                call splitting(d_held, pm, ok, itol)
            else
                call inner(dbar, pm, ok, itol)
            end if
        end subroutine solve_at

        !> z = y + gamma M^-1 A (y + h), the splitting's fixed point were y (= g) the solution
        !> (one FFT pair)
        subroutine start_splitting()
            call gcg_combine(COMBINE_SUM, f%t%x, g, h0)
            call multiply_buffer(SPECTRAL_START, gamma)
            call gcg_combine(COMBINE_SUM, z, g, f%t%x)
            state%operator_applications = state%operator_applications + 1
        end subroutine start_splitting

        !> Douglas-Rachford in the metric |A| (see the module's header), y is g: at mean gap `dbar`
        !> when the mean gap is held, else at the target load (`dbar` then the mean gap found)
        subroutine splitting(dbar, pm, ok, itol)
            real(dp), intent(inout) :: dbar
            real(dp), intent(in) :: itol
            real(dp), intent(out) :: pm
            logical, intent(out) :: ok
            real(dp), parameter :: inner_fraction = 0.3_dp
            real(dp) :: err, lam, ptmp, best, err_check
            !> the mean mode's metric retune_mean gives (0: none)
            real(dp) :: m_tuned
            logical :: iok
            integer :: n_outer, n_best, n_doubled, n_snap
            !> the mean gap read every mean_window outer iterations (the last n_snap of 3)
            real(dp) :: snaps(3)
            ok = .false.; tight = .false.
            n_snap = 0; snaps = 0.0_dp
            best = huge(1.0_dp); n_outer = 0; n_best = 0
            inner_cap = inner_steps; err_check = huge(1.0_dp)
            n_doubled = 0
            if (hold_mean) then
                ! the mean gap moves with z's
                call subtract(z, -(dbar - total(z)/cells))
                call keep_mean(dbar)
            end if
            do
                ! the residual of y on the operator itself (under load control the gradient
                ! holds the load: lambda = -target)
                call apply_operator(g, r)
                state%operator_applications = state%operator_applications + 1
                if (hold_mean) then
                    call gradient(lam, err)
                else
                    call gradient(lam, err, -target)
                    dbar = total(g)/cells
                end if
                pm = -lam
                if (err <= itol) then
                    ok = .true.; tight = itol <= tol; exit
                end if
                ! (stalled at the round-off: stop there)
                n_outer = n_outer + 1
                ! (too inexact: the inner solves' bound doubles)
                if (mod(n_outer, patience) == 0) then
                    if (err > progress*err_check) then
                        if (inner_cap < huge(inner_cap)/2) inner_cap = 2*inner_cap
                        n_doubled = n_doubled + 1
                    else
                        n_doubled = 0
                    end if
                    err_check = err
                    ! (no progress with the inner solves far from bounded: the metric floored,
                    ! the splitting restarted from y)
                    if (n_doubled >= rescue_after .and. .not. floored) then
                        if (floor_metric()) then
                            call start_splitting()
                            if (hold_mean) call subtract(z, -(dbar - total(z)/cells))
                            best = huge(1.0_dp); n_best = n_outer; err_check = huge(1.0_dp)
                            inner_cap = inner_steps; n_doubled = 0
                        end if
                    end if
                end if
                ! (under load control, a mean gap that converges slowly: its metric retuned once;
                ! not where the inner solves' bound has doubled or the metric is floored, where the
                ! slowness is the splitting's own; restored for the last digits)
                if (.not. (hold_mean .or. retuned .or. floored) .and. inner_cap == inner_steps .and. &
                    mod(n_outer, mean_window) == 0) then
                    snaps = eoshift(snaps, 1, dbar); n_snap = min(n_snap + 1, 3)
                    if (n_snap == 3) then
                        m_tuned = retune_mean(snaps)
                        if (m_tuned > 0.0_dp) then
                            m_first = mean_metric
                            call set_mean_metric(m_tuned)
                            retuned = .true.
                        end if
                    end if
                end if
                if (retuned .and. .not. restored .and. err < restore_below) then
                    call set_mean_metric(m_first); restored = .true.
                end if
                if (err < 0.9_dp*best) then
                    best = err; n_best = n_outer
                else if (n_outer - n_best >= stall_outer .and. best <= stall_band*floor_tol) then
                    call stalled(err); ok = .true.; tight = .true.; exit
                end if
                if (its >= opts%max_iterations .or. dev .and. device_failed()) exit
                call ticker%tick(its, err, state%operator_applications)
                ! x = the resolvent of z (in x), v = 2x - z as the inner heights' negative
                call gcg_combine(COMBINE_SUM, f%t%x, z, h0)
                call multiply_buffer(SPECTRAL_RESOLVENT, gamma)
                state%operator_applications = state%operator_applications + 1
                ! (the load's constant part of the operator, on the mean mode of the metric)
                call gcg_combine(COMBINE_DIFFERENCE, x, f%t%x, h0, merge(0.0_dp, gamma*target/mean_metric, hold_mean))
                call gcg_combine(COMBINE_REFLECT, hn, z, x)
                ! y: the symmetric problem with M/gamma, warm-started from the last y
                call inner(dbar, ptmp, iok, max(0.01_dp*itol, inner_fraction*err))
                call hn%assign(h0)
                call gcg_combine(COMBINE_ACCUMULATE, z, g, x, relaxation)
            end do
        end subroutine splitting

        !> out = A a (zero mean) with A the operator itself (with the splitting, not the inner
        !> solves' M/gamma), one FFT pair
        subroutine apply_operator(a, out)
            type(rarray_t), intent(in) :: a
            type(rarray_t), intent(inout) :: out
            if (.not. split) then
                call gcg_combine(COMBINE_SUM, f%t%x, a, hn)
                call multiply_buffer(SPECTRAL_A, 0.0_dp, out); return
            end if
            call gcg_combine(COMBINE_SUM, f%t%x, a, h0)
            call multiply_buffer(SPECTRAL_OPERATOR, 0.0_dp, out)
        end subroutine apply_operator

        !> From r = A (g + h): the gradient in `at` (less its mean over the free set, `lam`; zero
        !> off the free set), the free set, and `err` (max |gradient| over the open cells,
        !> max(-gradient) over the closed)
        subroutine gradient(lam, err, fixed)
            real(dp), intent(out) :: lam, err
            !> lambda given (the load), not the mean over the free set; 0 for an inner solve
            !> that does not hold the mean gap
            real(dp), intent(in), optional :: fixed
            real(dp) :: rows(3, ny), sums(3)
            logical :: held
            ! gradient and the free set: lambda from the open cells, then the closed cells
            ! that pull away join; a cell held at the Dugdale zone's edge (g = rho, attraction
            ! anywhere in [0, sigma0]: the law's graph there) stays while some attraction
            ! balances it, else leaves inward (sigma0) or outward (0)
            call gcg_attract(kind, s0, rho, g, r, at, edge, rows)
            call ordered_sum(problem%kernel%grid, rows, sums)
            held = sums(3) > 0.0_dp
            if (present(fixed)) then
                lam = fixed
            else if (.not. hold_mean) then
                lam = 0.0_dp
            else
                lam = 0.0_dp
                if (sums(2) > 0.0_dp) lam = sums(1)/sums(2)
            end if
            call gcg_free_set(g, r, at, free, edge, lam, s0, held, rows(1:2, :))
            if (hold_mean .and. .not. present(fixed)) then
                call ordered_sum(problem%kernel%grid, rows(1:2, :), sums(1:2))
                lam = 0.0_dp
                if (sums(2) > 0.0_dp) lam = sums(1)/sums(2)
            end if
            ! converged: no gradient on the open cells, none pulling a closed one away
            call gcg_centre(g, at, free, edge, lam, err)
            call global_max(problem%kernel%grid, err)
        end subroutine gradient

        !> The inner solve at mean gap `dbar`: g updated, r = A (g + h) on exit, `pm` the mean pressure
        subroutine inner(dbar, pm, ok, itol)
            real(dp), intent(in) :: dbar
            !> its tolerance
            real(dp), intent(in) :: itol
            real(dp), intent(out) :: pm
            logical, intent(out) :: ok
            !> r is carried along a step (r - tau A t) while no cell is clipped or shifted, and
            !> formed afresh at least this often (and before the solve ends)
            integer, parameter :: refresh = 50
            real(dp) :: lam, err, gsq, gsq_prev, tau, num, den, shift, beta, gmin, rows(4, ny), sums(4)
            !> the direction's new part: the gradient (at) or its preconditioned form (pz)
            type(rarray_t), pointer :: zd
            logical :: restart, fresh, moved, shifted
            !> the last step clipped cells and kept the conjugacy (few_clipped)
            logical :: kept
            real(dp) :: n_free
            integer :: n_inner, carried, n_best
            real(dp) :: tol_in, best
            logical :: stall, capped
            ! (once a solve stalled at the round-off, never below the estimated floor or where it
            ! stalled, the lower: it would not end)
            tol_in = itol
            if (at_floor) tol_in = max(itol, min(floor_tol, reached))
            best = huge(1.0_dp); n_best = 0
            tight = .false.
            if (hold_mean) call keep_mean(dbar)
            gsq_prev = 1.0_dp; restart = .true.; kept = .false.
            call fill(t, 0.0_dp)
            n_inner = 0
            ok = .false.
            fresh = .false.
            carried = 0
            do
                if (.not. fresh) then
                    call gcg_combine(COMBINE_SUM, f%t%x, g, hn)
                    call multiply_buffer(SPECTRAL_A, 0.0_dp, r)
                    state%operator_applications = state%operator_applications + 1
                    fresh = .true.; carried = 0
                end if
                call gradient(lam, err)
                pm = -lam
                ! (stalled at the round-off: stop there)
                if (err < 0.9_dp*best) then
                    best = err; n_best = n_inner
                end if
                stall = split .and. n_inner - n_best >= stall_inner .and. best <= stall_band*floor_tol
                ! (the splitting's bound: y as far as it got, r not needed, the outer iteration
                ! forms its own)
                capped = split .and. n_inner >= inner_cap .and. err > tol_in
                if (err <= tol_in .or. stall .or. capped .or. n_inner >= opts%max_iterations .or. &
                    dev .and. device_failed()) then
                    ! (confirmed on a fresh r when it was carried)
                    if (carried > 0 .and. .not. capped .and. .not. (dev .and. device_failed())) then
                        fresh = .false.; cycle
                    end if
                    ok = err <= tol_in; tight = ok .and. tol_in <= tol
                    if (stall .and. .not. ok) then
                        call stalled(err); ok = .true.; tight = .true.
                    end if
                    exit
                end if
                n_inner = n_inner + 1
                its = its + 1
                if (.not. split) call ticker%tick(its, err, state%operator_applications)
                ! the search direction on the free set (0 elsewhere: the gradient is), from the
                ! gradient (zero mean over the free set where the mean gap is held: gradient's
                ! lambda), or from it preconditioned (its mean over the free set removed again
                ! where the mean gap is held, so that a step keeps it)
                zd => at
                if (preconditioned) then
                    ! (pz = K at, K the inverse of the inner operator's multiplier where the law's
                    ! slope is added: A, or M/gamma in the splitting)
                    call f%t%x%assign(at)
                    call multiply_buffer(SPECTRAL_K, law_stiffness, pz)
                    state%operator_applications = state%operator_applications + 1
                    call gcg_mask(pz, free, rows(1:2, :))
                    shift = 0.0_dp
                    if (hold_mean) then
                        call ordered_sum(problem%kernel%grid, rows(1:2, :), sums(1:2))
                        if (sums(2) > 0.0_dp) shift = sums(1)/sums(2)
                    end if
                    call gcg_shift_dot(pz, at, free, shift, rows(1:1, :))
                    zd => pz
                else
                    call gcg_dot(at, at, rows(1:1, :))
                end if
                call ordered_sum(problem%kernel%grid, rows(1:1, :), sums(1:1))
                gsq = sums(1)
                beta = 0.0_dp
                if (.not. restart .and. gsq_prev > 0.0_dp) beta = max(gsq/gsq_prev, 0.0_dp)
                call gcg_direction(zd, at, t, free, beta, rows(1:1, :))
                call ordered_sum(problem%kernel%grid, rows(1:1, :), sums(1:1))
                num = sums(1)
                ! (a direction carried past a step that clipped cells that is no longer one of
                ! descent: the conjugacy restarts here instead)
                if (kept .and. .not. num > 0.0_dp .and. beta > 0.0_dp) then
                    call gcg_direction(zd, at, t, free, 0.0_dp, rows(1:1, :))
                    call ordered_sum(problem%kernel%grid, rows(1:1, :), sums(1:1))
                    num = sums(1)
                end if
                gsq_prev = gsq
                ! the step along t with A's curvature (the mean over the free set removed: the
                ! mean gap is held); pz = A t
                call f%t%x%assign(t)
                call multiply_buffer(SPECTRAL_A, 0.0_dp, pz)
                state%operator_applications = state%operator_applications + 1
                call gcg_curvature(pz, t, free, rows)
                call ordered_sum(problem%kernel%grid, rows, sums)
                den = sums(1); n_free = sums(3)
                if (hold_mean) then
                    if (sums(3) > 0.0_dp) then
                        den = den - (sums(2)/sums(3))*sums(4)
                    else
                        den = den - 0.0_dp*sums(4)
                    end if
                end if
                if (.not. (den > 0.0_dp)) then
                    if (carried > 0 .or. .not. fresh) then
                        call gcg_combine(COMBINE_SUM, f%t%x, g, hn)
                        call multiply_buffer(SPECTRAL_A, 0.0_dp, r)
                        state%operator_applications = state%operator_applications + 1
                    end if
                    exit
                end if
                tau = num/den
                call gcg_step(kind, rho, g, t, tau, edge, rows(1:2, :), gmin)
                call global_min(problem%kernel%grid, gmin)
                ! a step that clipped cells (closed them) restarts the conjugacy; in the
                ! splitting's inner solves not where it clipped at most `few_clipped` (kept)
                moved = gmin < 0.0_dp
                restart = moved
                kept = .false.
                if (kind == LAW_DUGDALE .or. split .and. moved) &
                    call ordered_sum(problem%kernel%grid, rows(1:2, :), sums(1:2))
                if (split .and. moved) then
                    kept = sums(2) <= min(few_clipped, few_share*n_free)
                    restart = .not. kept
                end if
                if (kind == LAW_DUGDALE) then
                    ! a step across the zone's edge stops there (the attraction's jump: a bound
                    ! like the contact's, and the conjugacy restarts)
                    if (sums(1) > 0.0_dp) then
                        restart = .true.; moved = .true.; kept = .false.
                    end if
                end if
                if (kept) n_kept = n_kept + 1
                if (hold_mean) then
                    call keep_mean(dbar, shifted)
                    moved = moved .or. shifted
                end if
                ! r = A (g + h) of the new g: along the step when g moved by -tau t alone
                if (moved .or. carried >= refresh) then
                    fresh = .false.
                else
                    call gcg_combine(COMBINE_AXPY, r, pz, pz, tau)
                    fresh = .true.; carried = carried + 1
                end if
            end do
        end subroutine inner

        !> The open cells shifted so that the mean gap is `dbar` (cells a shift closes are closed
        !> and the rest shifted again)
        subroutine keep_mean(dbar, shifted)
            real(dp), intent(in) :: dbar
            !> some cell was shifted
            logical, intent(out), optional :: shifted
            real(dp) :: gap_sum, open, rows(2, ny), sums(2), gmin
            integer :: pass
            !> a shift left negative gaps, to be clipped (as the next pass's sums are taken)
            logical :: clip
            if (present(shifted)) shifted = .false.
            clip = .false.
            do pass = 1, 50
                call gcg_gap_sums(g, clip, rows)
                clip = .false.
                call ordered_sum(problem%kernel%grid, rows, sums)
                gap_sum = sums(1); open = sums(2)
                if (open <= 0.0_dp) then
                    call subtract(g, -(dbar - gap_sum/cells))
                    if (present(shifted)) shifted = .true.
                    exit
                end if
                if (abs(dbar*cells - gap_sum) <= 1.0e-15_dp*max(abs(dbar)*cells, 1.0_dp)) exit
                call gcg_shift_open(g, (dbar*cells - gap_sum)/open, gmin)
                ! (a shift of the summed gap's round-off, after a step that keeps the mean, is not
                ! one: A (g + h) carried along such a step errs by round-off, and is formed afresh
                ! every 50 steps)
                if (present(shifted)) shifted = shifted .or. &
                    abs(dbar*cells - gap_sum) > 1.0e-12_dp*max(abs(dbar)*cells, 1.0_dp)
                call global_min(problem%kernel%grid, gmin)
                if (.not. gmin < 0.0_dp) exit
                clip = .true.
            end do
            if (clip) call gcg_gap_sums(g, .true., rows)
        end subroutine keep_mean

        !> The FFT buffer's field times the multiplier `mode` (SPECTRAL_*: A, the preconditioner
        !> K = 1/(A + c1), the operator, the resolvent or the start, c1 = gamma), one FFT pair; into
        !> `out` when given, else left in the buffer
        subroutine multiply_buffer(mode, c1, out)
            integer(c_int), intent(in) :: mode
            real(dp), intent(in) :: c1
            type(rarray_t), intent(inout), optional :: out
            call f%t%forward()
            call gcg_spectral(mode, f%t%k, a_s, k_s, c1, cells)
            call f%t%backward_unscaled()
            if (present(out)) call out%assign(f%t%x)
        end subroutine multiply_buffer

        !> The inner solves' preconditioner: the operator's inverse where the operator is stiffer
        !> than the law, 1/(A + k) with k the steepest slope of the attraction (s0/rho for the
        !> exponential law). It costs an FFT pair an iteration and pays where it narrows the
        !> spectrum, so it is taken when (docs/adhesion.md, measured):
        !>  - the law's slope is at most `stiff_law` of the operator's stiffness at the grid's
        !>    scale (the largest A over the modes with |q| above half the largest): a steeper law
        !>    is the Hessian's other, negative, part, which the preconditioner does not see;
        !>  - and the operator stiffens toward the grid's scale, at least `stiffening` times its
        !>    softest long wave (|q| up to twice the smallest): a half-space (A ~ |q|), but not a
        !>    thin layer (stiffest at its longest waves, or flat), where it cost 1.1 to 3.4 times
        !>    the FFT pairs.
        !> Dugdale's law (a jump, no slope) takes none.
        subroutine choose_preconditioner()
            real(dp), parameter :: stiffening = 4.0_dp
            real(dp) :: a_fine, a_low, q_top, q_low, qn
            integer :: ia, ib
            q_top = 0.0_dp; q_low = huge(1.0_dp)
            do ib = 1, size(ainv, 2)
                do ia = 1, size(ainv, 1)
                    qn = wavenumber(ia, ib)
                    q_top = max(q_top, qn)
                    if (qn > 0.0_dp) q_low = min(q_low, qn)
                end do
            end do
            call global_max(problem%kernel%grid, q_top)
            call global_min(problem%kernel%grid, q_low)
            preconditioned = .false.
            law_stiffness = huge(1.0_dp)
            if (kind == LAW_EXPONENTIAL) law_stiffness = s0/rho
            if (q_low == huge(1.0_dp)) return                 ! (a single cell: no mode but the mean)
            a_fine = 0.0_dp; a_low = huge(1.0_dp)
            do ib = 1, size(ainv, 2)
                do ia = 1, size(ainv, 1)
                    qn = wavenumber(ia, ib)
                    if (qn >= 0.5_dp*q_top) a_fine = max(a_fine, ainv(ia, ib))
                    if (qn > 0.0_dp .and. qn <= 2.0_dp*q_low .and. ainv(ia, ib) > 0.0_dp) a_low = min(a_low, ainv(ia, ib))
                end do
            end do
            call global_max(problem%kernel%grid, a_fine)
            call global_min(problem%kernel%grid, a_low)
            preconditioned = a_fine > 0.0_dp .and. law_stiffness <= stiff_law*a_fine*cells .and. &
                             a_fine >= stiffening*a_low
        end subroutine choose_preconditioner

        !> |q| of the mode at (ia, ib) of the half-spectrum's storage (this process's columns)
        real(dp) function wavenumber(ia, ib) result(qn)
            integer, intent(in) :: ia, ib
            integer :: ij(2)
            ij = problem%kernel%grid%spectral_index(ia, ib)
            qn = norm2(problem%kernel%grid%wavevector(ij(1), ij(2)))
        end function wavenumber

        !> A solve stopped where its gradient `err` stalled at the round-off
        subroutine stalled(err)
            real(dp), intent(in) :: err
            at_floor = .true.
            reached = max(reached, err)
        end subroutine stalled

        !> The round-off floor of the gradient's largest entry, in units of p_s, estimated: the
        !> gradient A (g + h) + sigma(g) is formed from heights of order h_s (one, in these units)
        !> that carry a rounding error of order epsilon each, white across the modes, which A
        !> amplifies mode by mode; FFTW's or cuFFT's own error is of the same order. So the
        !> largest entry over the grid cannot be trusted below about round_off epsilon rms|A|, the
        !> rms over the modes, round_off = 14 (on the paper scene, docs/validity.md (10): an
        !> evaluation of A h errs by up to 4e-11 p_s at 4096^2, 2e-11 at 2048^2, growing with the
        !> grid's finest wavenumber; this estimate gives 6e-11 and 3e-11). With the splitting, the
        !> operator's |A| (before its step). Only the band in which a stalled gradient counts as
        !> round-off: where the round-off does not fill every mode (a profile whose rows are equal)
        !> it is far above it.
        real(dp) function round_off_floor() result(fl)
            real(dp), parameter :: round_off = 14.0_dp
            real(dp) :: modes, squares
            squares = ordered_sum_scalar(problem%kernel%grid, sum(ainv**2, dim=1), spectral=.true.)
            modes = ordered_sum_scalar(problem%kernel%grid, spread(real(size(ainv, 1), dp), 1, size(ainv, 2)), &
                                       spectral=.true.)
            fl = round_off*epsilon(1.0_dp)*sqrt(squares/modes)*cells
        end function round_off_floor

        !> The splitting's metric over its step, M/gamma (M = |A|), raised to the law's steepest
        !> slope k (law_stiffness, s0/rho) where it is softer, the mean mode left as it is: the inner
        !> problem, M/(2 gamma) |y - v|^2 + sum V(y), is then convex (V'' >= -k), its solution
        !> unique. Returns whether a mode changed (where none is softer than the law, or the law has
        !> no slope, nothing is done)
        logical function floor_metric() result(changed)
            real(dp) :: fl, qn
            integer :: ia, ib
            changed = .false.
            floored = .true.
            if (kind /= LAW_EXPONENTIAL) return
            fl = law_stiffness/cells
            do ib = 1, size(ainv, 2)
                do ia = 1, size(ainv, 1)
                    qn = wavenumber(ia, ib)
                    if (qn > 0.0_dp .and. ainv(ia, ib) < fl) then
                        ainv(ia, ib) = fl; changed = .true.
                    end if
                end do
            end do
            call global_any(problem%kernel%grid, changed)
            if (changed .and. dev) call a_s%upload(ainv)
        end function floor_metric

        !> The mean mode's metric for the contact's stiffness, from three mean gaps `d3` read
        !> `mean_window` outer iterations apart; 0 where they do not converge slowly. A model of
        !> one mode: where the operator has no stiffness (the mean mode of A is zero: the load is
        !> its constant part) and the law's side b, over-relaxed by lambda, the error falls by
        !> rate = 1 - lambda b/(m + b) an outer iteration in the metric m: b is read from the
        !> rate, and m = (lambda - 1) b makes it zero
        real(dp) function retune_mean(d3) result(m_new)
            real(dp), intent(in) :: d3(3)
            real(dp) :: e1, e2, rate, b
            m_new = 0.0_dp
            e1 = d3(2) - d3(1); e2 = d3(3) - d3(2)
            if (.not. (e1*e2 > 0.0_dp .and. abs(e2) < abs(e1))) return
            rate = (e2/e1)**(1.0_dp/mean_window)
            if (rate < slow_mean) return
            b = mean_metric*(1.0_dp - rate)/(relaxation - 1.0_dp + rate)
            m_new = max((relaxation - 1.0_dp)*b, least_mean*mean_metric)
        end function retune_mean

        !> The mean mode's metric set to `m_new`, M (z - y) kept on it (so z's other modes, and
        !> their progress, are kept)
        subroutine set_mean_metric(m_new)
            real(dp), intent(in) :: m_new
            real(dp) :: m_old
            integer :: ia, ib
            m_old = mean_metric
            do ib = 1, size(ainv, 2)
                do ia = 1, size(ainv, 1)
                    if (wavenumber(ia, ib) == 0.0_dp) ainv(ia, ib) = m_new/(cells*gamma)
                end do
            end do
            mean_metric = m_new
            if (dev) call a_s%upload(ainv)
            call subtract(z, -(m_old/m_new - 1.0_dp)*(total(z) - total(g))/cells)
        end subroutine set_mean_metric

        !> sum over the whole grid, row by row and then over the rows in order
        real(dp) function total(a) result(s)
            type(rarray_t), intent(in) :: a
            real(dp) :: rows(1, ny), t1(1)
            call row_sums(a, rows(1, :))
            call ordered_sum(problem%kernel%grid, rows, t1)
            s = t1(1)
        end function total

        !> the mean of r, which is zero but for round-off (A kills the mean mode)
        real(dp) function sum_mean_removed() result(m)
            m = total(r)/cells
        end function sum_mean_removed

        !> The compliance of the softest mode (1/the smallest non-zero A), in h_s per p_s
        real(dp) function lowest_compliance() result(c)
            real(dp) :: a
            a = minval(abs(ainv), mask=ainv /= 0.0_dp)*cells
            call global_min(problem%kernel%grid, a)
            c = 1.0_dp
            if (a > 0.0_dp .and. a < huge(1.0_dp)) c = 1.0_dp/a
        end function lowest_compliance

    end subroutine gap_conjugate_gradients

end module veslide_solver_gcg
