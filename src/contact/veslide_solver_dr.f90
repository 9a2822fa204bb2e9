!> Douglas-Rachford splitting with Anderson acceleration and step balancing, for the contact
!> problem whatever the symmetry of its operator (the viscoelastic case).
!>
!> The contact problem is the inclusion 0 in A(p) + B(p), A(p) = K p - h + (normal cone of
!> mean(p) = p_mean), B = the contact law's (the hard wall's: the normal cone of p >= 0). A is
!> monotone because Re K > 0, whether or not K is symmetric, so the splitting converges without
!> symmetry. In units p/p_mean, h/h_s, with step gamma, one iteration is
!>   x = (I + gamma K)^-1 (z + gamma h), mean(x) = 1   (one FFT pair: the kernel's resolvent)
!>   z <- z + c, c such that mean(prox(2x - z - c)) = 1   (the approach for the load)
!>   y = prox(2x - z),  f = y - x,   z <- z + f      (accelerated by Anderson mixing),
!> prox the law's proximal map (problem%law, veslide_contact_law; the hard wall's max(v, 0)),
!> applied by the passes that take the law.
!> At the fixed point x = y = p and z = p + gamma g. The resolvent fixes the mean of x, never
!> that of z: the mean of z is gamma times the mean gap (the approach), which the plain step
!> alone would move by mean(y) - 1 per iteration, the mean gap by (mean(y) - 1) h_s/gamma.
!> Where gamma is large (a stiff operator: a thin bonded incompressible layer, |K| p_mean/h_s
!> ~ 2e-5 and gamma ~ 5e4) that left y without contact (y = 0, f = -x = -1 everywhere: a
!> plateau of |f| on which the mixing and its safeguard see nothing) until the balancing had
!> shrunk gamma below round-off (docs/solvers.md). The shift c, the one number that makes y
!> carry the load, is found exactly instead (Newton's method on a convex piecewise-linear
!> function of c, about 2.3 passes over x and z per iteration); it moves only the mean of z,
!> which x does not see, and is 0 at the fixed point. So y always carries the load, as the
!> projection of `solver_pdr` does. The step is balanced every
!> `balance_every` iterations between the pressure residual (x where y is out of contact) and
!> the gap residual (f/gamma where it is in contact), by factors of `balance_factor`, with z remapped to the new
!> step. An accelerated step whose residual grew by more than `aa_growth` is replaced by the
!> plain step and the memory cleared. Convergence is confirmed on y with a fresh K y.
!> Lions & Mercier, SIAM J. Numer. Anal. 16 (1979) 964; docs/solvers.md for the measurements.
module veslide_solver_dr
    use veslide_kinds, only: dp
    use veslide_kernel, only: resolvent_t
    use veslide_contact, only: contact_problem_t, contact_state_t, contact_fields_t
    use veslide_solver_options, only: solver_options_t, progress_ticker_t
    use veslide_anderson, only: anderson_t
    use veslide_collective, only: global_max, ordered_sum
    use veslide_arrays, only: rarray_t, carray_t
    use veslide_passes, only: centre_divide, divided_copy
    use veslide_dr_passes, only: dr_rebalance, dr_project, dr_restore, dr_add_gap, dr_load_sums, dr_shift
    use veslide_device, only: device_failed
    implicit none
    private
    public :: douglas_rachford

contains

    !> The iteration is memory-bound outside its FFT pair, so the map is fused into the two passes
    !> of the Anderson mixing (`anderson_t`, memory m; the map's residual is the reflection of the
    !> resolvent's output, computed on the way):
    !>   A  `columns`: the map (y = max(2x - z, 0), f = y - x, the residuals) with the new history
    !>      columns dF = f - f_prev, G = (z - z_prev) + dF and their inner products;
    !>   B  `update`: z <- z + f - G c (f recomputed from x and z), keeping (z, f), and the next
    !>      map's input written straight into the FFT buffer.
    !> y and f are never stored. A path that skips pass B (the safeguard, balancing) clears the
    !> history, whose newest column pass A has already written. The sums are row by row and then
    !> over the rows in order (veslide_collective), so the path is the same for any number of
    !> threads or processes.
    subroutine douglas_rachford(problem, f, opts, state, gap0)
        type(contact_problem_t), intent(in) :: problem
        type(contact_fields_t), intent(inout) :: f
        type(solver_options_t), intent(in) :: opts
        !> on entry the starting pressure (problem%start, in f%p); on exit the solution
        type(contact_state_t), intent(inout) :: state
        !> gap of the starting pressure [m] (default: zero gap)
        real(dp), intent(in), optional :: gap0(:, :)
        real(dp), parameter :: aa_growth = 2.0_dp
        type(rarray_t) :: z
        type(carray_t) :: hkern
        type(anderson_t) :: aa
        type(resolvent_t) :: res
        real(dp) :: gamma, hs, inner_tol, fnorm, fnorm_prev, rp, rg, rsq, s, scale, p_mean
        real(dp) :: coef(max(opts%anderson_memory, 1)), part(1 + 2*max(opts%anderson_memory, 1)), ext(2)
        integer :: nx, ny, since_balance, m, mk
        logical :: accelerated
        type(progress_ticker_t) :: ticker

        nx = f%p%n1; ny = f%p%n2
        hs = problem%height_scale_m
        p_mean = problem%p_mean_pa
        state%method = 'dr'
        call ticker%start(opts, 'dr')
        scale = p_mean/hs                       ! K in units of h_s per p_mean
        call centre_divide(f%t%x, f%h, problem%h_mean, hs)
        call f%t%forward()
        call hkern%create(f%t%k%n1, f%t%k%n2, f%device)
        call hkern%assign(f%t%k)
        gamma = opts%step
        if (.not. (gamma > 0.0_dp)) gamma = 1.0_dp/problem%kernel%typical_abs(scale)
        call res%set(f%kd, gamma, scale, problem%kernel%grid%cells(), problem%kernel%grid%owns_mean_mode())

        m = max(0, opts%anderson_memory)
        call z%create(nx, ny, f%device)
        call aa%init(nx, ny, m, f%device, problem%kernel%grid)
        call divided_copy(z, f%p, p_mean)       ! z = p + gamma g
        if (present(gap0)) then
            if (f%gap_held) then
                call f%t%x%assign(f%g)                ! gap0, kept on the device from a study's last case
            else
                call f%t%x%upload(gap0)
            end if
            call dr_add_gap(z, f%t%x, gamma, hs)
        end if
        accelerated = .false.
        fnorm_prev = huge(1.0_dp); since_balance = 0
        inner_tol = opts%tolerance
        call f%t%x%assign(z)

        do
            ! the map: x = resolvent(z) (left in the FFT buffer, which holds z on entry)
            call res%solve(f%t, hkern, gamma, 1.0_dp)
            state%operator_applications = state%operator_applications + 1
            call carry_load()

            ! pass A: y, f = y - x and the residuals; the new history column and its products
            mk = aa%begin()
            call aa%columns(f%t%x, z, mk, part, rp, rg, law=problem%law)
            ext = [rp, rg]
            call global_max(problem%kernel%grid, ext)
            rsq = part(1); rp = ext(1); rg = ext(2)/gamma
            fnorm = sqrt(rsq)
            if (f%device) then
                if (device_failed()) exit
            end if

            ! safeguard: an accelerated step that made |f| grow is replaced by the plain step
            if (accelerated) then          ! (nested: fnorm_prev may still be huge() otherwise)
                if (fnorm > aa_growth*fnorm_prev) then
                    call dr_restore(f%t%x, z, aa%zprev, aa%fprev)
                    call clear_history()
                    cycle
                end if
            end if

            if (max(rp, rg) <= inner_tol) then
                call dr_project(problem%law, f%p, f%t%x, z, p_mean)
                call problem%confirm(f, state, opts%tolerance)
                if (state%converged) exit
                inner_tol = inner_tol/10.0_dp
                if (inner_tol < 1.0e-15_dp) exit
                ! evaluate the map again at z (the same point: pass A rewrites the same column)
                call aa%again(mk)
                call f%t%x%assign(z)
                cycle
            end if
            if (state%iterations >= opts%max_iterations) then
                call dr_project(problem%law, f%p, f%t%x, z, p_mean)
                call problem%confirm(f, state, opts%tolerance)
                exit
            end if
            state%iterations = state%iterations + 1
            call ticker%tick(state%iterations, max(rp, rg), state%operator_applications)

            ! step balancing between pressure and gap residuals
            since_balance = since_balance + 1
            if (since_balance >= opts%balance_every .and. max(rp, rg) > 0.0_dp) then
                since_balance = 0
                s = 1.0_dp
                if (rg > opts%balance_ratio*rp) s = opts%balance_factor
                if (rp > opts%balance_ratio*rg) s = 1.0_dp/opts%balance_factor
                if (s /= 1.0_dp) then
                    ! z = y + s (z - y): z = p + gamma g remapped to the new gamma
                    call dr_rebalance(problem%law, f%t%x, z, s)
                    gamma = gamma*s
                    call res%set(f%kd, gamma, scale, problem%kernel%grid%cells(), &
                                 problem%kernel%grid%owns_mean_mode())
                    call clear_history()
                    fnorm_prev = huge(1.0_dp)
                    cycle
                end if
            end if

            ! the mixing coefficients, then pass B: z <- z + f - G c, keeping (z, f); the next
            ! map's input into the buffer
            mk = aa%mix(part, mk, coef)
            accelerated = mk > 0
            call aa%update(f%t%x, z, coef, mk, law=problem%law)
            fnorm_prev = fnorm
        end do
        call z%destroy(); call aa%destroy(); call hkern%destroy(); call res%destroy()

    contains

        !> Forget the mixing history (after a change of the map, or a rejected step)
        subroutine clear_history()
            call aa%reset(); accelerated = .false.
        end subroutine clear_history

        !> z <- z + c with the c that makes y = prox(2x - z) carry the load: with v = 2x - z,
        !> phi(c) = sum(prox(v - c)) - N = 0 (N cells). For the hard wall phi is convex, piecewise
        !> linear and decreasing with slope -count(v > c) (the cells prox puts in contact):
        !> Newton's method from a c with phi >= 0 stays below the root and is exact once that
        !> count stops changing (from phi < 0 its first step lands below the root). Starts at
        !> c = 0, or without contact there (count 0) at c = max v - N, where phi >= 0.
        subroutine carry_load()
            integer, parameter :: max_steps = 100
            real(dp) :: c, c_new, phi, cnt, cnt_new, vmax, cells
            integer :: k
            cells = problem%kernel%grid%cells()
            c = 0.0_dp
            call load_sums(c, phi, cnt, vmax)
            if (cnt == 0.0_dp) then
                c = vmax - cells
                call load_sums(c, phi, cnt, vmax)
            end if
            do k = 1, max_steps
                if (phi == 0.0_dp .or. cnt == 0.0_dp) exit
                c_new = c + phi/cnt
                if (c_new == c) exit
                call load_sums(c_new, phi, cnt_new, vmax)
                c = c_new
                if (cnt_new == cnt) exit
                cnt = cnt_new
            end do
            if (c /= 0.0_dp .and. abs(c) <= huge(1.0_dp)) call dr_shift(z, c)
        end subroutine carry_load

        !> phi(c) and count(v > c) over the whole grid, v = 2x - z; vmax = max v
        subroutine load_sums(c, phi, cnt, vmax)
            real(dp), intent(in) :: c
            real(dp), intent(out) :: phi, cnt, vmax
            real(dp) :: rows(2, ny), t(2)
            call dr_load_sums(problem%law, f%t%x, z, c, rows, vmax)
            call ordered_sum(problem%kernel%grid, rows, t)
            call global_max(problem%kernel%grid, vmax)
            phi = t(1) - problem%kernel%grid%cells(); cnt = t(2)
        end subroutine load_sums

    end subroutine douglas_rachford

end module veslide_solver_dr
