!> Douglas-Rachford splitting with Anderson acceleration and step balancing, for the contact
!> problem whatever the symmetry of its operator (the viscoelastic case).
!>
!> The contact problem is the inclusion 0 in A(p) + B(p), A(p) = K p - h + (normal cone of
!> mean(p) = p_mean), B = normal cone of p >= 0. A is monotone because Re K > 0, whether or
!> not K is symmetric, so the splitting converges without symmetry. In units p/p_mean,
!> h/h_s, with step gamma, one iteration is
!>   x = (I + gamma K)^-1 (z + gamma h), mean(x) = 1   (one FFT pair: the kernel's resolvent)
!>   y = max(2x - z, 0),  f = y - x,   z <- z + f      (accelerated by Anderson mixing).
!> At the fixed point x = y = p and z = p + gamma g. The step is balanced every
!> `balance_every` iterations between the pressure residual (x where y = 0) and the gap
!> residual (f/gamma where y > 0), by factors of `balance_factor`, with z remapped to the new
!> step. An accelerated step whose residual grew by more than `aa_growth` is replaced by the
!> plain step and the memory cleared. Convergence is confirmed on y with a fresh K y.
!> Lions & Mercier, SIAM J. Numer. Anal. 16 (1979) 964; docs/solvers.md for the measurements.
module veslide_solver_dr
    use veslide_kinds, only: dp
    use veslide_kernel, only: resolvent_t
    use veslide_contact, only: contact_problem_t, contact_state_t, contact_fields_t
    use veslide_solver_options, only: solver_options_t, progress_ticker_t
    use veslide_anderson, only: anderson_coefficients
    use veslide_collective, only: ordered_sum, global_max
    use veslide_arrays, only: rarray_t, carray_t, sarray_t
    use veslide_passes, only: centre_divide, divided_copy
    use veslide_dr_passes, only: dr_map, dr_update, dr_rebalance, dr_project, dr_restore, dr_add_gap
    use veslide_device, only: device_failed
    implicit none
    private
    public :: douglas_rachford

contains

    !> The iteration is memory-bound outside its FFT pair, so the map and the Anderson mixing
    !> (type II, as `anderson_t`, memory m) are fused into two passes over the grid
    !> (veslide_dr_passes):
    !>   A  the map (y = max(2x - z, 0), f = y - x, the residuals) with the new history columns
    !>      dF = f - f_prev, G = (z - z_prev) + dF and their inner products with the history;
    !>   B  z <- z + f - G c (f recomputed from x and z), keeping (z, f), and the next map's input
    !>      written straight into the FFT buffer.
    !> y and f are never stored. A path that skips pass B (the safeguard, balancing) clears the
    !> history, whose newest column pass A has already written. Pass A sums row by row and then
    !> over the rows in order (veslide_collective), so the path is the same for any number of
    !> threads or processes. The history is single precision: it halves the memory traffic of the
    !> mixing, which is then exact to about 1e-7 of the step, absorbed by the fixed-point
    !> iteration (the residual itself is double).
    subroutine douglas_rachford(problem, f, opts, state, gap0)
        type(contact_problem_t), intent(in) :: problem
        type(contact_fields_t), intent(inout) :: f
        type(solver_options_t), intent(in) :: opts
        !> on entry the starting pressure (problem%start, in f%p); on exit the solution
        type(contact_state_t), intent(inout) :: state
        !> gap of the starting pressure [m] (default: zero gap)
        real(dp), intent(in), optional :: gap0(:, :)
        real(dp), parameter :: aa_growth = 2.0_dp
        type(rarray_t) :: z, zprev, fprev
        type(sarray_t) :: df, gm
        type(carray_t) :: hkern
        real(dp), allocatable :: gram(:, :)
        type(resolvent_t) :: res
        real(dp) :: gamma, hs, inner_tol, fnorm, fnorm_prev, rp, rg, rsq, s, scale, p_mean
        real(dp) :: coef(max(opts%anderson_memory, 1)), dots(max(opts%anderson_memory, 1), 2)
        real(dp) :: part(1 + 2*max(opts%anderson_memory, 1)), ext(2)
        real(dp), allocatable :: rows(:, :)
        integer :: nx, ny, n, since_balance, m, slot, mk, stored, info
        logical :: accelerated, have_prev
        type(progress_ticker_t) :: ticker

        nx = f%p%n1; ny = f%p%n2; n = nx*ny
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
        call z%create(nx, ny, f%device); call zprev%create(nx, ny, f%device); call fprev%create(nx, ny, f%device)
        call df%create(n, max(m, 1), f%device); call gm%create(n, max(m, 1), f%device)
        allocate (gram(max(m, 1), max(m, 1)), rows(1 + 2*max(m, 1), ny))
        call divided_copy(z, f%p, p_mean)       ! z = p + gamma g
        if (present(gap0)) then
            call f%t%x%upload(gap0)
            call dr_add_gap(z, f%t%x, gamma, hs)
        end if
        have_prev = .false.; stored = 0; slot = 0
        accelerated = .false.
        fnorm_prev = huge(1.0_dp); since_balance = 0
        inner_tol = opts%tolerance
        call f%t%x%assign(z)

        do
            ! the map: x = resolvent(z) (left in the FFT buffer, which holds z on entry)
            call res%solve(f%t, hkern, gamma, 1.0_dp)
            state%operator_applications = state%operator_applications + 1

            ! pass A: y, f = y - x and the residuals; the new history column and its products
            mk = 0
            if (m > 0 .and. have_prev) then
                slot = modulo(slot, m) + 1; mk = min(stored + 1, m)
            end if
            call dr_map(f%t%x, z, df, gm, zprev, fprev, slot, mk, rows, rp, rg)
            call ordered_sum(problem%kernel%grid, rows(1:1 + 2*mk, :), part(1:1 + 2*mk))
            ext = [rp, rg]
            call global_max(problem%kernel%grid, ext)
            rsq = part(1); rp = ext(1); rg = ext(2)/gamma
            dots(1:mk, 1) = part(2:1 + mk); dots(1:mk, 2) = part(2 + mk:1 + 2*mk)
            fnorm = sqrt(rsq)
            if (f%device) then
                if (device_failed()) exit
            end if

            ! safeguard: an accelerated step that made |f| grow is replaced by the plain step
            if (accelerated) then          ! (nested: fnorm_prev may still be huge() otherwise)
                if (fnorm > aa_growth*fnorm_prev) then
                    call dr_restore(f%t%x, z, zprev, fprev)
                    call clear_history()
                    cycle
                end if
            end if

            if (max(rp, rg) <= inner_tol) then
                call dr_project(f%p, f%t%x, z, p_mean)
                call problem%confirm(f, state, opts%tolerance)
                if (state%converged) exit
                inner_tol = inner_tol/10.0_dp
                if (inner_tol < 1.0e-15_dp) exit
                ! evaluate the map again at z (the same point: pass A rewrites the same column)
                if (mk > 0) slot = modulo(slot - 2, m) + 1
                call f%t%x%assign(z)
                cycle
            end if
            if (state%iterations >= opts%max_iterations) then
                call dr_project(f%p, f%t%x, z, p_mean)
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
                    call dr_rebalance(f%t%x, z, s)
                    gamma = gamma*s
                    call res%set(f%kd, gamma, scale, problem%kernel%grid%cells(), &
                                 problem%kernel%grid%owns_mean_mode())
                    call clear_history()
                    fnorm_prev = huge(1.0_dp)
                    cycle
                end if
            end if

            ! the mixing coefficients from the updated Gram matrix
            info = 1
            if (mk > 0) then
                gram(1:mk, slot) = dots(1:mk, 1); gram(slot, 1:mk) = dots(1:mk, 1)
                call anderson_coefficients(gram, mk, dots(1:mk, 2), coef, info)
            end if
            if (info /= 0) then
                mk = 0; stored = 0
            else
                stored = mk
            end if
            accelerated = mk > 0

            ! pass B: z <- z + f - G c, keeping (z, f); the next map's input into the buffer
            call dr_update(f%t%x, z, gm, zprev, fprev, coef, mk)
            have_prev = .true.
            fnorm_prev = fnorm
        end do
        call z%destroy(); call zprev%destroy(); call fprev%destroy(); call df%destroy(); call gm%destroy()
        call hkern%destroy(); call res%destroy()

    contains

        !> Forget the mixing history (after a change of the map, or a rejected step)
        subroutine clear_history()
            have_prev = .false.; stored = 0; slot = 0; accelerated = .false.
        end subroutine clear_history

    end subroutine douglas_rachford

end module veslide_solver_dr
