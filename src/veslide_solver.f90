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
    use veslide_kinds, only: dp
    use veslide_error, only: error_t, fatal_error
    use veslide_fftw, only: fft2d_t
    use veslide_kernel, only: kernel_t
    implicit none
    private
    public :: solver_options_t, contact_state_t, solve_contact, apply_operator, contact_residuals

    type :: solver_options_t
        character(len=16) :: method = 'auto'   !! 'auto', 'pk' or 'dr'
        real(dp) :: tolerance = 1.0e-10_dp      !! target of the residual [-]
        integer :: max_iterations = 20000       !! iteration cap
        integer :: refresh_every = 200          !! recompute K p exactly this often (pk)
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
    subroutine solve_contact(kernel, fft, h, p_mean, opts, state, error, p_init)
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
            call fatal_error(error, "veslide:solver:solve_contact: method 'dr' is not available yet"); return
        case default
            call fatal_error(error, "veslide:solver:solve_contact: unknown method '"//trim(method)//"'"); return
        end select
    end subroutine solve_contact

    !> Polonsky & Keer (1999) constrained conjugate gradient, load control
    subroutine polonsky_keer(fft, mult, hc, p_mean, opts, state)
        type(fft2d_t), intent(inout) :: fft
        complex(dp), intent(in) :: mult(:, :)
        real(dp), intent(in) :: hc(:, :), p_mean
        type(solver_options_t), intent(in) :: opts
        type(contact_state_t), intent(inout) :: state
        real(dp), allocatable :: g(:, :), t(:, :), r(:, :), pn(:, :), c(:, :), kc(:, :)
        logical, allocatable :: act(:, :)
        real(dp) :: gbar, rbar, gg, gg_old, tau, den, scale, delta
        integer :: nc, since_fresh
        logical :: fresh, changed

        allocate (g, t, r, pn, c, kc, mold=hc)
        allocate (act(size(hc, 1), size(hc, 2)))
        call apply_operator(fft, mult, state%p, state%u)
        state%operator_applications = 1
        fresh = .true.; since_fresh = 0
        t = 0.0_dp; delta = 0.0_dp; gg_old = 1.0_dp
        do
            call contact_residuals(state, hc, p_mean)
            if (state%residual <= opts%tolerance) then
                if (fresh) then
                    state%converged = .true.; exit
                end if
                call refresh()
                cycle
            end if
            if (state%iterations >= opts%max_iterations) exit
            state%iterations = state%iterations + 1

            act = state%p > 0.0_dp
            nc = count(act)
            g = state%u - hc
            gbar = sum(g, mask=act)/nc
            g = g - gbar
            gg = sum(g*g, mask=act)
            where (act)
                t = g + delta*(gg/gg_old)*t
            elsewhere
                t = 0.0_dp
            end where
            gg_old = gg
            call apply_operator(fft, mult, t, r)
            state%operator_applications = state%operator_applications + 1
            rbar = sum(r, mask=act)/nc
            den = sum((r - rbar)*t, mask=act)
            if (.not. (den > 0.0_dp)) then
                ! no descent left: only round-off remains, confirm on a fresh product
                if (fresh) exit
                call refresh(); cycle
            end if
            tau = sum(g*t, mask=act)/den
            pn = state%p - tau*t
            pn = max(pn, 0.0_dp)
            if (any(pn == 0.0_dp .and. g < 0.0_dp)) then
                delta = 0.0_dp
                where (pn == 0.0_dp .and. g < 0.0_dp) pn = pn - tau*g
            else
                delta = 1.0_dp
            end if
            ! c = what projection and re-admission added to the linear step
            c = pn - (state%p - tau*t)
            changed = any(c /= 0.0_dp)
            scale = p_mean*size(pn)/sum(pn)
            state%p = scale*pn
            state%u = state%u - tau*r
            if (changed) then
                call apply_operator(fft, mult, c, kc)
                state%operator_applications = state%operator_applications + 1
                state%u = state%u + kc
            end if
            state%u = scale*state%u
            fresh = .false.
            since_fresh = since_fresh + 1
            if (since_fresh >= opts%refresh_every) call refresh()
        end do

    contains

        subroutine refresh()
            call apply_operator(fft, mult, state%p, state%u)
            state%operator_applications = state%operator_applications + 1
            fresh = .true.; since_fresh = 0
        end subroutine refresh

    end subroutine polonsky_keer

end module veslide_solver
