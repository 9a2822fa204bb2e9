!> Load-controlled periodic contact of a rigid surface on a half-space:
!>   find p >= 0 with mean(p) = p_mean, and an approach d, such that the gap
!>   g = K p - h + d >= 0 and p g = 0 everywhere.
!> K is the kernel's multiplier (zero on the mean mode), h the heights with their mean removed;
!> d is then the mean gap (mean separation).
!>
!> Methods:
!>  - 'pk': Polonsky-Keer constrained conjugate gradient (symmetric operators: the elastic case).
!>    The displacement is updated linearly (u <- s (u - tau K t)), so an iteration costs one
!>    operator application (one FFT pair) unless the active set changed, when the correction
!>    K c of the clipped/re-admitted points costs one more.
!>
!! One convergence measure is used for every method (see `contact_state_t`):
!!   residual = max(penetration, complementarity, negative pressure, load error), with
!!   penetration = max(-g)/h_s, complementarity = |sum p g|/(sum p * h_s),
!!   negative pressure = max(-p)/p_mean, load error = |mean p - p_mean|/p_mean,
!!   h_s = rms height (or the displacement scale p_mean*max|K| for a flat surface).
!! Convergence is always confirmed on a freshly computed K p (no accumulated round-off).
module veslide_solver
    use, intrinsic :: iso_c_binding, only: c_f_pointer, c_loc
    use veslide_kinds, only: dp
    use veslide_error, only: error_t, fatal_error
    use veslide_fftw, only: fft2d_t
    use veslide_kernel, only: kernel_t
    use veslide_lapack, only: dposv
    implicit none
    private
    public :: solver_options_t, contact_state_t, solve_contact, apply_operator, contact_residuals

    type :: solver_options_t
        character(len=16) :: method = 'auto'   !! 'auto', 'pk' or 'dr'
        real(dp) :: tolerance = 1.0e-10_dp      !! target of the residual [-]
        integer :: max_iterations = 20000       !! iteration cap
        integer :: refresh_every = 200          !! recompute K p exactly this often (pk)
        integer :: anderson_memory = 5          !! Anderson mixing depth (dr); 0 switches it off
        integer :: balance_every = 50           !! step-size balancing interval (dr)
        real(dp) :: step = 0.0_dp               !! initial dimensionless step (dr); 0: automatic
        real(dp) :: balance_ratio = 10.0_dp     !! imbalance of the residuals that changes the step (dr)
        real(dp) :: balance_factor = 3.0_dp     !! factor the step changes by (dr)
    end type solver_options_t

    type :: contact_state_t
        real(dp), allocatable :: p(:, :)        !! pressure [Pa]
        real(dp), allocatable :: u(:, :)        !! zero-mean displacement K p, positive into the solid [m]
        real(dp), allocatable :: g(:, :)        !! gap [m], >= 0 up to the tolerance
        real(dp) :: approach_m = 0.0_dp         !! d: the mean gap [m]
        integer :: iterations = 0
        integer :: operator_applications = 0    !! FFT pairs spent on K
        logical :: converged = .false.
        real(dp) :: penetration = huge(1.0_dp), complementarity = huge(1.0_dp)
        real(dp) :: negative_pressure = huge(1.0_dp), load_error = huge(1.0_dp)
        real(dp) :: residual = huge(1.0_dp)
        real(dp) :: height_scale_m = 0.0_dp     !! h_s of the residual [m]
        character(len=:), allocatable :: method  !! method used
    end type contact_state_t

contains

    !> out = K f (real space, zero mean), using fft's buffers; `mult` is K_d/(nx*ny)
    subroutine apply_operator(fft, mult, f, out)
        type(fft2d_t), intent(inout) :: fft
        complex(dp), intent(in) :: mult(:, :)
        real(dp), intent(in) :: f(:, :)
        real(dp), intent(out) :: out(:, :)
        fft%x = f
        call fft%forward()
        fft%k = fft%k*mult
        call fft%backward_unscaled()
        out = fft%x
    end subroutine apply_operator

    !> Residuals of a candidate (p, u): fills d, g and the four measures of `state`
    subroutine contact_residuals(state, hc, p_mean)
        type(contact_state_t), intent(inout) :: state
        real(dp), intent(in) :: hc(:, :), p_mean
        real(dp) :: gsum, psum
        integer :: nc
        nc = count(state%p > 0.0_dp)
        state%g = state%u - hc
        if (nc > 0) then
            state%approach_m = -sum(state%g, mask=state%p > 0.0_dp)/nc
        else
            state%approach_m = -maxval(state%g)
        end if
        state%g = state%g + state%approach_m
        gsum = sum(state%p*state%g)
        psum = sum(abs(state%p))
        state%penetration = max(0.0_dp, -minval(state%g))/state%height_scale_m
        state%complementarity = abs(gsum)/(psum*state%height_scale_m)
        state%negative_pressure = max(0.0_dp, -minval(state%p))/p_mean
        state%load_error = abs(sum(state%p)/size(state%p) - p_mean)/p_mean
        state%residual = max(state%penetration, state%complementarity, state%negative_pressure, state%load_error)
    end subroutine contact_residuals

    !> Solve the contact problem; `p_init` warm-starts from a previous pressure
    subroutine solve_contact(kernel, fft, h, p_mean, opts, state, error, p_init, g_init)
        type(kernel_t), intent(in) :: kernel
        type(fft2d_t), intent(inout) :: fft
        !> rigid heights [m] (any mean)
        real(dp), intent(in) :: h(:, :)
        !> nominal pressure [Pa]
        real(dp), intent(in) :: p_mean
        type(solver_options_t), intent(in) :: opts
        type(contact_state_t), intent(out) :: state
        type(error_t), allocatable, intent(out) :: error
        real(dp), intent(in), optional :: p_init(:, :)
        !> gap that goes with p_init [m] (the splitting method starts from both)
        real(dp), intent(in), optional :: g_init(:, :)
        real(dp), allocatable :: hc(:, :)
        complex(dp), allocatable :: mult(:, :)
        integer :: nx, ny
        character(len=16) :: method

        nx = size(h, 1); ny = size(h, 2)
        if (nx /= kernel%nx .or. ny /= kernel%ny .or. nx /= fft%nx .or. ny /= fft%ny) then
            call fatal_error(error, "veslide:solver:solve_contact: heights, kernel and FFT grids differ"); return
        end if
        if (.not. (p_mean > 0.0_dp)) then
            call fatal_error(error, "veslide:solver:solve_contact: the nominal pressure must be positive"); return
        end if
        if (any(h /= h)) then
            call fatal_error(error, "veslide:solver:solve_contact: the heights contain NaN"); return
        end if
        method = opts%method
        if (method == 'auto') method = merge('pk', 'dr', kernel%symmetric)
        if (method == 'pk' .and. .not. kernel%symmetric) then
            call fatal_error(error, "veslide:solver:solve_contact: method 'pk' needs a symmetric (elastic)"// &
                " kernel; use 'dr' or 'auto'"); return
        end if

        hc = h - sum(h)/size(h)
        mult = kernel%kd/(real(nx, dp)*real(ny, dp))
        allocate (state%p(nx, ny), state%u(nx, ny), state%g(nx, ny))
        state%height_scale_m = sqrt(sum(hc**2)/size(hc))
        if (state%height_scale_m <= 0.0_dp) state%height_scale_m = p_mean*maxval(abs(kernel%kd))
        if (state%height_scale_m <= 0.0_dp) state%height_scale_m = 1.0_dp

        state%p = p_mean
        if (present(p_init)) then
            if (all(shape(p_init) == [nx, ny])) then
                if (sum(max(p_init, 0.0_dp)) > 0.0_dp) then
                    state%p = max(p_init, 0.0_dp)
                    state%p = state%p*(p_mean*size(state%p)/sum(state%p))
                end if
            end if
        end if

        select case (method)
        case ('pk')
            state%method = 'pk'
            call polonsky_keer(fft, mult, hc, p_mean, opts, state)
        case ('dr')
            state%method = 'dr'
            if (present(p_init) .and. present(g_init)) then
                call douglas_rachford(fft, kernel%kd, hc, p_mean, opts, state, gap0=g_init)
            else
                call douglas_rachford(fft, kernel%kd, hc, p_mean, opts, state)
            end if
        case default
            call fatal_error(error, "veslide:solver:solve_contact: unknown method '"//trim(method)//"'"); return
        end select
    end subroutine solve_contact

    !> Polonsky & Keer (1999) constrained conjugate gradient, load control.
    !>
    !> The iteration is memory-bound outside its one FFT pair, so it is written as four fused,
    !> OpenMP-parallel passes over the grid and keeps no gap array:
    !>   A  residuals, contact-set mean of the gap and |g|^2 (sums shifted by the previous mean,
    !>      so that no cancellation spoils them near convergence);
    !>   C  conjugate direction t, written straight into the FFT buffer, with sum(g t), sum(t);
    !>   -  r = K t (the FFT pair);
    !>   D  step-length sums;  E  step, projection p >= 0, re-admission, u <- u - tau r.
    !> The load rescaling p, u <- s p, s u is kept as a pending scalar `a` (true p = a P). The
    !> displacement is carried along linearly; the correction K c for the points that projection
    !> or re-admission changed costs one more FFT pair in the iterations that have any, unless
    !> there is a single such point (then one shifted column of the influence function is added).
    subroutine polonsky_keer(fft, mult, hc, p_mean, opts, state)
        type(fft2d_t), intent(inout) :: fft
        complex(dp), intent(in) :: mult(:, :)
        real(dp), intent(in) :: hc(:, :), p_mean
        type(solver_options_t), intent(in) :: opts
        type(contact_state_t), intent(inout) :: state
        real(dp), allocatable :: t(:, :), green(:, :)
        real(dp) :: a, gp, gbar, s1, s2, gg, gg_old, beta, tau, den, num, sr, srt, st, sp_new, pv, g, pn, hs
        real(dp) :: gmin, spg, sp, pmin, c1, delta, uo, c
        integer :: nx, ny, i, j, nc, m, since_fresh, ic, jc
        logical :: fresh, have_green
        integer :: noverlap

        nx = size(hc, 1); ny = size(hc, 2)
        hs = state%height_scale_m
        allocate (t(nx, ny))
        have_green = .false.
        call apply_operator(fft, mult, state%p, state%u)
        state%operator_applications = 1
        fresh = .true.; since_fresh = 0
        t = 0.0_dp; delta = 0.0_dp; gg_old = 1.0_dp; a = 1.0_dp
        gp = sum(state%u - hc, mask=state%p > 0.0_dp)/max(1, count(state%p > 0.0_dp))
        do
            ! pass A: residuals and contact-set statistics of g = a U - h, shifted by gp
            nc = 0; s1 = 0.0_dp; s2 = 0.0_dp; gmin = huge(1.0_dp); spg = 0.0_dp; sp = 0.0_dp; pmin = huge(1.0_dp)
            !$omp parallel do private(i, pv, g) reduction(+:nc, s1, s2, spg, sp) reduction(min:gmin, pmin)
            do j = 1, ny
                do i = 1, nx
                    pv = a*state%p(i, j)
                    g = a*state%u(i, j) - hc(i, j) - gp
                    if (pv > 0.0_dp) then
                        nc = nc + 1; s1 = s1 + g; s2 = s2 + g*g
                    end if
                    gmin = min(gmin, g)
                    spg = spg + pv*g
                    sp = sp + pv
                    pmin = min(pmin, pv)
                end do
            end do
            !$omp end parallel do
            c1 = s1/nc
            gbar = gp + c1
            gg = max(s2 - s1*c1, 0.0_dp)
            state%approach_m = -gbar
            state%penetration = max(0.0_dp, -(gmin - c1))/hs
            state%complementarity = abs(spg - c1*sp)/(sp*hs)
            state%negative_pressure = max(0.0_dp, -pmin)/p_mean
            state%load_error = abs(sp/(real(nx, dp)*ny) - p_mean)/p_mean
            state%residual = max(state%penetration, state%complementarity, state%negative_pressure, &
                                 state%load_error)
            gp = gbar
            if (state%residual <= opts%tolerance) then
                if (fresh) then
                    state%converged = .true.; exit
                end if
                call refresh(); cycle
            end if
            if (state%iterations >= opts%max_iterations) exit
            state%iterations = state%iterations + 1

            ! pass C: conjugate direction on the contact set, straight into the FFT buffer
            beta = delta*gg/gg_old
            gg_old = gg
            num = 0.0_dp; st = 0.0_dp
            !$omp parallel do private(i, g) reduction(+:num, st)
            do j = 1, ny
                do i = 1, nx
                    if (state%p(i, j) > 0.0_dp) then
                        g = a*state%u(i, j) - hc(i, j) - gbar
                        t(i, j) = g + beta*t(i, j)
                        num = num + g*t(i, j)
                        st = st + t(i, j)
                    else
                        t(i, j) = 0.0_dp
                    end if
                    fft%x(i, j) = t(i, j)
                end do
            end do
            !$omp end parallel do
            call fft%forward()
            fft%k = fft%k*mult
            call fft%backward_unscaled()          ! fft%x = r = K t
            state%operator_applications = state%operator_applications + 1

            ! pass D: step length, with r centred on the contact set
            sr = 0.0_dp; srt = 0.0_dp
            !$omp parallel do private(i) reduction(+:sr, srt)
            do j = 1, ny
                do i = 1, nx
                    if (state%p(i, j) > 0.0_dp) then
                        sr = sr + fft%x(i, j)
                        srt = srt + fft%x(i, j)*t(i, j)
                    end if
                end do
            end do
            !$omp end parallel do
            den = srt - sr/nc*st
            if (.not. (den > 0.0_dp)) then
                ! no descent left: only round-off remains, confirm on a fresh product
                if (fresh) exit
                call refresh(); cycle
            end if
            tau = num/den

            ! pass E: step, projection, re-admission of overlapping points, displacement update.
            ! r is not needed after its use here, so the buffer takes the correction c (what
            ! projection and re-admission add to the linear step).
            m = 0; sp_new = 0.0_dp; noverlap = 0; ic = 0; jc = 0
            !$omp parallel do private(i, pn, g, uo, c) reduction(+:m, sp_new, noverlap) reduction(max:ic, jc)
            do j = 1, ny
                do i = 1, nx
                    uo = a*state%u(i, j)
                    pn = a*state%p(i, j) - tau*t(i, j)
                    state%u(i, j) = uo - tau*fft%x(i, j)
                    c = 0.0_dp
                    if (pn < 0.0_dp) then
                        c = -pn
                        pn = 0.0_dp
                    end if
                    if (pn == 0.0_dp) then
                        g = uo - hc(i, j) - gbar
                        if (g < 0.0_dp) then
                            noverlap = noverlap + 1
                            c = c - tau*g
                            pn = -tau*g
                        end if
                    end if
                    fft%x(i, j) = c
                    if (c /= 0.0_dp) then
                        m = m + 1; ic = max(ic, i); jc = max(jc, j)
                    end if
                    state%p(i, j) = pn
                    sp_new = sp_new + pn
                end do
            end do
            !$omp end parallel do
            delta = merge(0.0_dp, 1.0_dp, noverlap > 0)
            if (m > 0) call add_correction(m, ic, jc)
            a = p_mean*(real(nx, dp)*ny)/sp_new
            fresh = .false.
            since_fresh = since_fresh + 1
            if (since_fresh >= opts%refresh_every) call refresh()
        end do
        state%p = a*state%p
        state%u = a*state%u
        state%g = state%u - hc - gbar

    contains

        !> U = K P exactly, with the pending scale applied first
        subroutine refresh()
            state%p = a*state%p; a = 1.0_dp
            call apply_operator(fft, mult, state%p, state%u)
            state%operator_applications = state%operator_applications + 1
            fresh = .true.; since_fresh = 0
        end subroutine refresh

        !> u += K c for the correction held in the FFT buffer (m non-zeros; for m = 1 at (ic, jc))
        subroutine add_correction(m, ic, jc)
            integer, intent(in) :: m, ic, jc
            integer :: ii, jj, i0, j0, js
            real(dp) :: cv
            if (m > 1) then
                call fft%forward()
                fft%k = fft%k*mult
                call fft%backward_unscaled()
                state%u = state%u + fft%x
                state%operator_applications = state%operator_applications + 1
                return
            end if
            cv = fft%x(ic, jc)
            if (.not. have_green) then
                fft%k = mult
                call fft%backward_unscaled()
                green = fft%x        ! K applied to a unit pressure on cell (1, 1)
                have_green = .true.
                state%operator_applications = state%operator_applications + 1
            end if
            i0 = ic - 1; j0 = jc - 1
            do jj = 1, ny
                js = modulo(jj - 1 - j0, ny) + 1
                do ii = 1, i0
                    state%u(ii, jj) = state%u(ii, jj) + cv*green(nx - i0 + ii, js)
                end do
                do ii = i0 + 1, nx
                    state%u(ii, jj) = state%u(ii, jj) + cv*green(ii - i0, js)
                end do
            end do
        end subroutine add_correction

    end subroutine polonsky_keer


    !> Douglas-Rachford splitting with Anderson acceleration and step balancing.
    !>
    !> The contact problem is the inclusion 0 in A(p) + B(p), A(p) = K p - h + (normal cone of
    !> mean(p) = p_mean), B = normal cone of p >= 0. A is monotone because Re K > 0, whether or
    !> not K is symmetric, so the splitting converges without symmetry. In units p/p_mean,
    !> h/h_s, with step gamma, one iteration is
    !>   x = (I + gamma K)^-1 (z + gamma h), mean(x) = 1   (one FFT pair: a Fourier multiplier)
    !>   y = max(2x - z, 0),  f = y - x,   z <- z + f      (accelerated by Anderson mixing).
    !> At the fixed point x = y = p and z = p + gamma g. The step is balanced every
    !> `balance_every` iterations between the pressure residual (x where y = 0) and the gap
    !> residual (f/gamma where y > 0), by factors of 3, with z remapped to the new step.
    !> Anderson (type II, memory m) keeps the columns dF = f_k - f_{k-1} and G = dz + dF, so one
    !> iteration costs one FFT pair, one pass over 2m columns and a few over the grid; the m x m
    !> least-squares problem is solved from its Gram matrix (LAPACK dposv).
    !> An accelerated step whose residual grew by more than `aa_growth` is replaced by the plain
    !> step and the memory cleared. Convergence is confirmed on y with a fresh K y.
    subroutine douglas_rachford(fft, kd, hc, p_mean, opts, state, gap0)
        type(fft2d_t), intent(inout) :: fft
        complex(dp), intent(in) :: kd(:, :)
        real(dp), intent(in) :: hc(:, :), p_mean
        type(solver_options_t), intent(in) :: opts
        type(contact_state_t), intent(inout) :: state
        !> gap of the starting pressure [m] (default: zero gap)
        real(dp), intent(in), optional :: gap0(:, :)
        real(dp), parameter :: aa_growth = 2.0_dp
        real(dp), allocatable, target :: zz(:, :)
        real(dp), pointer :: z(:), xb(:)
        real(dp), allocatable :: y(:), f(:), zprev(:), fprev(:), dfm(:, :), gm(:, :)
        complex(dp), allocatable :: ks(:, :), hk(:, :), res(:, :)
        real(dp), allocatable :: gram(:, :), gtmp(:, :), coef(:), dots(:, :)
        real(dp) :: gamma, hs, inner_tol, fnorm, fnorm_prev, rp, rg, rsq, s, xv, dfv, zn
        integer :: nx, ny, n, mmax, mk, slot, k, info, since_balance, i
        logical :: accelerated, have_prev

        nx = size(hc, 1); ny = size(hc, 2); n = nx*ny
        hs = state%height_scale_m
        mmax = max(0, opts%anderson_memory)
        ks = kd*(p_mean/hs)                     ! dimensionless multiplier
        fft%x = hc/hs
        call fft%forward()
        hk = fft%k
        gamma = opts%step
        if (.not. (gamma > 0.0_dp)) gamma = 1.0_dp/exp(sum(log(abs(ks) + tiny(1.0_dp)), mask=abs(ks) > 0.0_dp) &
                                                     /max(1, count(abs(ks) > 0.0_dp)))
        call make_resolvent()

        allocate (zz(nx, ny), y(n), f(n), zprev(n), fprev(n))
        allocate (dfm(n, max(mmax, 1)), gm(n, max(mmax, 1)))
        allocate (gram(max(mmax, 1), max(mmax, 1)), gtmp(max(mmax, 1), max(mmax, 1)), coef(max(mmax, 1)))
        allocate (dots(max(mmax, 1), 2))
        z(1:n) => zz
        call c_f_pointer(c_loc(fft%x), xb, [n])    ! a flat view of the FFT buffer
        zz = state%p/p_mean                     ! z = p + gamma g
        if (present(gap0)) zz = zz + gamma*gap0/hs
        mk = 0; slot = 0; have_prev = .false.; accelerated = .false.
        fnorm_prev = huge(1.0_dp); since_balance = 0
        inner_tol = opts%tolerance

        do
            ! the map: x = resolvent(z) (left in the FFT buffer), y = projection, f = y - x
            fft%x = zz
            call fft%forward()
            fft%k = res*(fft%k + gamma*hk)
            fft%k(1, 1) = 1.0_dp
            call fft%backward_unscaled()
            state%operator_applications = state%operator_applications + 1
            rp = 0.0_dp; rg = 0.0_dp; rsq = 0.0_dp
            !$omp parallel do private(xv) reduction(max:rp, rg) reduction(+:rsq)
            do i = 1, n
                xv = xb(i)
                y(i) = max(2.0_dp*xv - z(i), 0.0_dp)
                f(i) = y(i) - xv
                if (y(i) > 0.0_dp) then
                    rg = max(rg, abs(f(i)))
                else
                    rp = max(rp, abs(xv))
                end if
                rsq = rsq + f(i)**2
            end do
            !$omp end parallel do
            rg = rg/gamma
            fnorm = sqrt(rsq)

            ! safeguard: an accelerated step that made |f| grow is replaced by the plain step
            if (accelerated) then          ! (nested: fnorm_prev may still be huge() otherwise)
                if (fnorm > aa_growth*fnorm_prev) then
                    z = zprev + fprev
                    mk = 0; accelerated = .false.; have_prev = .false.
                    cycle
                end if
            end if

            if (max(rp, rg) <= inner_tol) then
                state%p = p_mean*reshape(y, [nx, ny])
                call apply_operator(fft, kd/real(n, dp), state%p, state%u)
                state%operator_applications = state%operator_applications + 1
                call contact_residuals(state, hc, p_mean)
                if (state%residual <= opts%tolerance) then
                    state%converged = .true.; exit
                end if
                inner_tol = inner_tol/10.0_dp
                if (inner_tol < 1.0e-15_dp) exit
                cycle      ! the buffer no longer holds x: evaluate the map again at z
            end if
            if (state%iterations >= opts%max_iterations) then
                state%p = p_mean*reshape(y, [nx, ny])
                call apply_operator(fft, kd/real(n, dp), state%p, state%u)
                call contact_residuals(state, hc, p_mean)
                exit
            end if
            state%iterations = state%iterations + 1

            ! step balancing between pressure and gap residuals
            since_balance = since_balance + 1
            if (since_balance >= opts%balance_every .and. max(rp, rg) > 0.0_dp) then
                since_balance = 0
                s = 1.0_dp
                if (rg > opts%balance_ratio*rp) s = opts%balance_factor
                if (rp > opts%balance_ratio*rg) s = 1.0_dp/opts%balance_factor
                if (s /= 1.0_dp) then
                    z = y + s*(z - y)           ! z = p + gamma g, remapped to the new gamma
                    gamma = gamma*s
                    call make_resolvent()
                    mk = 0; have_prev = .false.; accelerated = .false.; fnorm_prev = huge(1.0_dp)
                    cycle
                end if
            end if

            ! Anderson mixing (type II) on the fixed-point residual f, in two fused passes:
            ! new columns with the Gram row and right-hand side, then the update of z
            accelerated = .false.
            if (mmax > 0 .and. have_prev) then
                slot = modulo(slot, mmax) + 1
                mk = min(mk + 1, mmax)
                dots = 0.0_dp
                !$omp parallel do private(dfv, k) reduction(+:dots)
                do i = 1, n
                    dfv = f(i) - fprev(i)
                    dfm(i, slot) = dfv
                    gm(i, slot) = (z(i) - zprev(i)) + dfv
                    do k = 1, mk
                        dots(k, 1) = dots(k, 1) + dfm(i, k)*dfv
                        dots(k, 2) = dots(k, 2) + dfm(i, k)*f(i)
                    end do
                end do
                !$omp end parallel do
                gram(1:mk, slot) = dots(1:mk, 1); gram(slot, 1:mk) = dots(1:mk, 1)
                gtmp(1:mk, 1:mk) = gram(1:mk, 1:mk)
                do k = 1, mk
                    gtmp(k, k) = gtmp(k, k)*(1.0_dp + 1.0e-10_dp)
                end do
                coef(1:mk) = dots(1:mk, 2)
                call dposv('U', mk, 1, gtmp, size(gtmp, 1), coef, size(coef), info)
                if (info /= 0) then
                    mk = 0; coef = 0.0_dp
                end if
                accelerated = info == 0
                !$omp parallel do private(zn, k)
                do i = 1, n
                    zn = z(i) + f(i)
                    do k = 1, mk
                        zn = zn - gm(i, k)*coef(k)
                    end do
                    zprev(i) = z(i); fprev(i) = f(i)
                    z(i) = zn
                end do
                !$omp end parallel do
            else
                zprev = z; fprev = f
                z = z + f
            end if
            have_prev = .true.
            fnorm_prev = fnorm
        end do

    contains

        !> res = 1/((1 + gamma K) N): the resolvent's multiplier, with FFTW's 1/N folded in
        subroutine make_resolvent()
            res = 1.0_dp/((1.0_dp + gamma*ks)*real(n, dp))
        end subroutine make_resolvent

    end subroutine douglas_rachford

end module veslide_solver
