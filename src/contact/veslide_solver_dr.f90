!> Douglas-Rachford splitting with Anderson acceleration and step balancing, for the contact
!> problem whatever the symmetry of its operator (the viscoelastic case).
!>
!> The contact problem is the inclusion 0 in A(p) + B(p), A(p) = K p - h + (normal cone of
!> mean(p) = p_mean), B = normal cone of p >= 0. A is monotone because Re K > 0, whether or
!> not K is symmetric, so the splitting converges without symmetry. In units p/p_mean,
!> h/h_s, with step gamma, one iteration is
!>   x = (I + gamma K)^-1 (z + gamma h), mean(x) = 1   (one FFT pair: the kernel's resolvent)
!>   y = max(2x - z, 0),  f = y - x,   z <- z + f      (accelerated by `anderson_t`).
!> At the fixed point x = y = p and z = p + gamma g. The step is balanced every
!> `balance_every` iterations between the pressure residual (x where y = 0) and the gap
!> residual (f/gamma where y > 0), by factors of `balance_factor`, with z remapped to the new
!> step. An accelerated step whose residual grew by more than `aa_growth` is replaced by the
!> plain step and the memory cleared. Convergence is confirmed on y with a fresh K y.
!> Lions & Mercier, SIAM J. Numer. Anal. 16 (1979) 964; docs/solvers.md for the measurements.
module veslide_solver_dr
    use, intrinsic :: iso_c_binding, only: c_f_pointer, c_loc
    use veslide_kinds, only: dp
    use veslide_fftw, only: fft2d_t
    use veslide_kernel, only: resolvent_t
    use veslide_contact, only: contact_problem_t, contact_state_t
    use veslide_solver_options, only: solver_options_t
    use veslide_anderson, only: anderson_t
    use veslide_collective, only: ordered_sum, global_max
    implicit none
    private
    public :: douglas_rachford

contains

    subroutine douglas_rachford(problem, fft, opts, state, gap0)
        type(contact_problem_t), intent(in) :: problem
        type(fft2d_t), intent(inout) :: fft
        type(solver_options_t), intent(in) :: opts
        !> on entry the starting pressure (problem%start); on exit the solution
        type(contact_state_t), intent(inout) :: state
        !> gap of the starting pressure [m] (default: zero gap)
        real(dp), intent(in), optional :: gap0(:, :)
        real(dp), parameter :: aa_growth = 2.0_dp
        real(dp), allocatable, target :: zz(:, :)
        real(dp), pointer :: z(:), xb(:)
        real(dp), allocatable :: y(:), f(:)
        complex(dp), allocatable :: hk(:, :)
        type(resolvent_t) :: res
        type(anderson_t) :: aa
        real(dp) :: gamma, hs, inner_tol, fnorm, fnorm_prev, rp, rg, rsq, s, xv, scale, p_mean, ext(2), tot(1), r1
        real(dp), allocatable :: rows(:, :)
        integer :: nx, ny, n, since_balance, i, j
        logical :: accelerated

        nx = size(problem%hc, 1); ny = size(problem%hc, 2); n = nx*ny
        hs = problem%height_scale_m
        p_mean = problem%p_mean_pa
        state%method = 'dr'
        scale = p_mean/hs                       ! K in units of h_s per p_mean
        fft%x = problem%hc/hs
        call fft%forward()
        hk = fft%k
        gamma = opts%step
        if (.not. (gamma > 0.0_dp)) gamma = 1.0_dp/problem%kernel%typical_abs(scale)
        call problem%kernel%resolvent(gamma, scale, res)

        allocate (zz(nx, ny), y(n), f(n), rows(1, ny))
        call aa%init(n, opts%anderson_memory, problem%kernel%grid)
        z(1:n) => zz
        call c_f_pointer(c_loc(fft%x), xb, [n])    ! a flat view of the FFT buffer
        zz = state%p/p_mean                     ! z = p + gamma g
        if (present(gap0)) zz = zz + gamma*gap0/hs
        accelerated = .false.
        fnorm_prev = huge(1.0_dp); since_balance = 0
        inner_tol = opts%tolerance

        do
            ! the map: x = resolvent(z) (left in the FFT buffer), y = projection, f = y - x
            fft%x = zz
            call res%solve(fft, hk, gamma, 1.0_dp)
            state%operator_applications = state%operator_applications + 1
            rp = 0.0_dp; rg = 0.0_dp
            !$omp parallel do private(i, xv, r1) reduction(max:rp, rg)
            do j = 1, ny
                r1 = 0.0_dp
                do i = (j - 1)*nx + 1, j*nx
                    xv = xb(i)
                    y(i) = max(2.0_dp*xv - z(i), 0.0_dp)
                    f(i) = y(i) - xv
                    if (y(i) > 0.0_dp) then
                        rg = max(rg, abs(f(i)))
                    else
                        rp = max(rp, abs(xv))
                    end if
                    r1 = r1 + f(i)**2
                end do
                rows(1, j) = r1
            end do
            !$omp end parallel do
            call ordered_sum(problem%kernel%grid, rows, tot)
            ext = [rp, rg]
            call global_max(problem%kernel%grid, ext)
            rp = ext(1); rsq = tot(1)
            rg = ext(2)/gamma
            fnorm = sqrt(rsq)

            ! safeguard: an accelerated step that made |f| grow is replaced by the plain step
            if (accelerated) then          ! (nested: fnorm_prev may still be huge() otherwise)
                if (fnorm > aa_growth*fnorm_prev) then
                    call aa%plain_step_from_previous(z)
                    accelerated = .false.
                    cycle
                end if
            end if

            if (max(rp, rg) <= inner_tol) then
                state%p = p_mean*reshape(y, [nx, ny])
                call problem%kernel%apply(fft, state%p, state%u)
                state%operator_applications = state%operator_applications + 1
                call problem%residuals(state)
                if (state%residual <= opts%tolerance) then
                    state%converged = .true.; exit
                end if
                inner_tol = inner_tol/10.0_dp
                if (inner_tol < 1.0e-15_dp) exit
                cycle      ! the buffer no longer holds x: evaluate the map again at z
            end if
            if (state%iterations >= opts%max_iterations) then
                state%p = p_mean*reshape(y, [nx, ny])
                call problem%kernel%apply(fft, state%p, state%u)
                call problem%residuals(state)
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
                    call problem%kernel%resolvent(gamma, scale, res)
                    call aa%reset(); accelerated = .false.; fnorm_prev = huge(1.0_dp)
                    cycle
                end if
            end if

            accelerated = aa%step(z, f)
            fnorm_prev = fnorm
        end do
    end subroutine douglas_rachford

end module veslide_solver_dr
