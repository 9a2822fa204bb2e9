!> The kernel as an operator: the multiplier's symmetries and definiteness per variant, and the
!> operations the solvers use (apply, impulse response, resolvent) against brute-force sums
module test_veslide_kernel
    use, intrinsic :: iso_fortran_env, only: qp => real128
    use veslide_kinds, only: dp, pi
    use veslide_error, only: error_t, ERROR_NUMERICAL, exit_status
    use veslide_grid, only: grid_t, new_grid
    use veslide_fftw, only: fft2d_t
    use veslide_arrays, only: carray_t
    use veslide_transform, only: transform_t
    use veslide_material, only: material_t, new_relaxation, new_one_term, new_elastic
    use veslide_kernel, only: kernel_t, resolvent_t, new_kernel, new_kernel_from_multiplier, KERNEL_SPECTRAL, &
                              KERNEL_COLLOCATION_ALIAS, KERNEL_GALERKIN
    use testsuite, only: unittest_t, new_unittest, check, report
    use reference_oracles, only: paper_solid, peak_speed, einf, tau, lcell
    implicit none
    private
    public :: collect_kernel

contains

    subroutine collect_kernel(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("kernel-hermitian", test_kernel_hermitian), &
            new_unittest("collocation-alias-loses-definiteness", test_definiteness, should_fail=.true., &
                         expect="not positive definite"), &
            new_unittest("lost-definiteness-is-a-numerical-error", test_definiteness_category), &
            new_unittest("galerkin-stays-definite", test_galerkin_definite), &
            new_unittest("apply-equals-influence-sum", test_apply_sum), &
            new_unittest("kernel-of-a-200-term-series", test_long_series), &
            new_unittest("resolvent-inverts-i-plus-gamma-k", test_resolvent), &
            new_unittest("multiplier-must-be-definite", test_from_multiplier, should_fail=.true., &
                         expect="not positive definite"), &
            new_unittest("shear-multiplies-every-mode", test_shear_multiplier), &
            new_unittest("shear-raises-re-k", test_shear_re_k), &
            new_unittest("shear-symmetry-flag", test_shear_symmetry), &
            new_unittest("shear-on-a-layer-refused", test_shear_layer, should_fail=.true., &
                         expect="interfacial shear on a layer is not available"), &
            new_unittest("shear-keeps-the-definiteness-refusal", test_shear_definiteness, should_fail=.true., &
                         expect="not positive definite") &
            ]
    end subroutine collect_kernel

    function cell_grid(nx, ny) result(grid)
        integer, intent(in) :: nx, ny
        type(grid_t) :: grid
        type(error_t), allocatable :: error
        call new_grid(grid, nx, ny, lcell, lcell*ny/nx, error)
    end function cell_grid

    !> K(-q) = conj K(q) on the stored column qx = 0 and on the Nyquist column
    subroutine test_kernel_hermitian(error)
        type(error_t), allocatable, intent(out) :: error
        type(material_t) :: m
        type(kernel_t) :: k
        integer, parameter :: n = 16
        integer :: j, jm
        real(dp) :: worst
        call paper_solid(100.0_dp, m, error); if (allocated(error)) return
        call new_kernel(k, cell_grid(n, n), m, peak_speed(100.0_dp, 2.0_dp)*[cos(0.3_dp), sin(0.3_dp)], &
                        KERNEL_SPECTRAL, error)
        if (allocated(error)) return
        worst = 0
        do j = 1, n
            jm = modulo(n - (j - 1), n) + 1
            worst = max(worst, abs(k%value(1, j) - conjg(k%value(1, jm))), &
                        abs(k%value(n/2 + 1, j) - conjg(k%value(n/2 + 1, jm))))
        end do
        call check(error, worst <= 1.0e-15_dp*k%max_abs(), "not Hermitian"); if (allocated(error)) return
        call check(error, .not. k%symmetric, "a viscoelastic kernel in motion is not symmetric")
    end subroutine test_kernel_hermitian

    !> Aliases nearly perpendicular to v see w ~ 0 (rubbery, large) times a negative sinc, while
    !> the mode itself is glassy: Re K_d < 0 (notes, section 7). With v along a grid axis the
    !> aliases share the mode's frequency and this cannot happen; at 15 degrees it does
    !> (an independent numpy sum gives min Re K_d < 0 for v tau/L from 0.1 to 100 here).
    subroutine test_definiteness(error)
        type(error_t), allocatable, intent(out) :: error
        type(kernel_t) :: k
        call oblique_kernel(KERNEL_COLLOCATION_ALIAS, k, error)
    end subroutine test_definiteness

    !> That failure is of the numbers, not of the input or a file: the programs exit with 4
    subroutine test_definiteness_category(error)
        type(error_t), allocatable, intent(out) :: error
        type(kernel_t) :: k
        type(error_t), allocatable :: e
        call oblique_kernel(KERNEL_COLLOCATION_ALIAS, k, e)
        call check(error, allocated(e), "collocation-alias kept its definiteness"); if (allocated(error)) return
        call check(error, e%category == ERROR_NUMERICAL .and. exit_status(e) == 4, &
                   "lost definiteness is not a numerical error (exit status 4)")
    end subroutine test_definiteness_category

    !> Einf/E0 = 1000, 32^2, v tau/L = 1 at 15 degrees: the case where collocation-alias fails
    subroutine oblique_kernel(variant, k, error)
        integer, intent(in) :: variant
        type(kernel_t), intent(out) :: k
        type(error_t), allocatable, intent(out) :: error
        type(material_t) :: m
        call paper_solid(1000.0_dp, m, error); if (allocated(error)) return
        call new_kernel(k, cell_grid(32, 32), m, lcell/tau*[cos(pi/12), sin(pi/12)], &
                        variant, error, alias_tol=1.0e-4_dp)
    end subroutine oblique_kernel

    subroutine test_galerkin_definite(error)
        type(error_t), allocatable, intent(out) :: error
        type(kernel_t) :: k
        call oblique_kernel(KERNEL_GALERKIN, k, error); if (allocated(error)) return
        call report("min Re K_d Einf L", k%min_re*einf/lcell)
        call check(error, k%min_re > 0.0_dp, "galerkin kernel lost definiteness")
    end subroutine test_galerkin_definite

    !> K p equals the sum over cells of p_j times the impulse response shifted to cell j (the
    !> influence-coefficient form of the same operator), for an oblique viscoelastic kernel
    subroutine test_apply_sum(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: nx = 8, ny = 6
        type(material_t) :: m
        type(kernel_t) :: k
        type(fft2d_t) :: fft
        real(dp) :: p(nx, ny), u(nx, ny), green(nx, ny), us(nx, ny)
        integer :: i, j
        call paper_solid(11.0_dp, m, error); if (allocated(error)) return
        call new_kernel(k, cell_grid(nx, ny), m, peak_speed(11.0_dp, 2.0_dp)*[cos(0.4_dp), sin(0.4_dp)], &
                        KERNEL_SPECTRAL, error)
        if (allocated(error)) return
        call fft%init(nx, ny, error, planner='estimate'); if (allocated(error)) return
        call random_number(p)
        call k%apply(fft, p, u)
        call k%impulse_response(fft, green)
        us = 0
        do j = 1, ny
            do i = 1, nx
                us = us + p(i, j)*cshift(cshift(green, -(i - 1), dim=1), -(j - 1), dim=2)
            end do
        end do
        call report("max |K p - sum|/max|K p|", maxval(abs(u - us))/maxval(abs(u)))
        call check(error, maxval(abs(u - us)) <= 1.0e-13_dp*maxval(abs(u)), "apply differs from the influence sum")
    end subroutine test_apply_sum

    !> A relaxation series of 200 terms (times 1e-15..1e25 s, 40 decades): its spectral kernel on
    !> a 32 x 24 grid, sliding along x (the compliance tabulated per column), along y (per row)
    !> and at 30 deg (per mode), equals 2 (1 - nu^2) C(-q.v)/|q| with C summed independently in
    !> quadruple precision at every mode's frequency (the two signs averaged on Nyquist lines),
    !> within 1e-13 of max |K| (measured 2e-16)
    subroutine test_long_series(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 200, nx = 32, ny = 24
        real(dp), parameter :: angles(3) = [0.0_dp, 90.0_dp, 30.0_dp]
        type(material_t) :: m
        type(kernel_t) :: k
        type(grid_t) :: grid
        real(dp) :: tau_j(n), e(n), v(2), q(2), worst, kmax
        complex(dp) :: kd
        integer :: j, i, jj, ia, rx, ry, nrx, nry
        do j = 1, n
            tau_j(j) = 10.0_dp**(-15.0_dp + 40.0_dp*(j - 1)/(n - 1))
            e(j) = 1.0e6_dp*(1.0_dp + 0.5_dp*sin(0.1_dp*j))
        end do
        call new_relaxation(m, 1.0e6_dp, e, tau_j, 0.45_dp, error); if (allocated(error)) return
        grid = cell_grid(nx, ny)
        worst = 0.0_dp
        do ia = 1, size(angles)
            v = 0.3_dp*[cos(angles(ia)*pi/180.0_dp), sin(angles(ia)*pi/180.0_dp)]
            if (ia == 2) v = [0.0_dp, 0.3_dp]
            call new_kernel(k, grid, m, v, KERNEL_SPECTRAL, error); if (allocated(error)) return
            kmax = 0.0_dp
            do jj = 1, ny
                do i = 1, nx/2 + 1
                    if (i == 1 .and. jj == 1) cycle
                    kmax = max(kmax, abs(k%value(i, jj)))
                end do
            end do
            do jj = 1, ny
                do i = 1, nx/2 + 1
                    if (i == 1 .and. jj == 1) cycle
                    nrx = merge(2, 1, grid%is_nyquist_x(i)); nry = merge(2, 1, grid%is_nyquist_y(jj))
                    kd = (0.0_dp, 0.0_dp)
                    do ry = 1, nry
                        do rx = 1, nrx
                            q = grid%wavevector(i, jj)
                            if (rx == 2) q(1) = -q(1)
                            if (ry == 2) q(2) = -q(2)
                            kd = kd + 2.0_dp*(1.0_dp - 0.45_dp**2)*quad_compliance(-dot_product(q, v))/norm2(q)
                        end do
                    end do
                    kd = kd/(nrx*nry)
                    worst = max(worst, abs(k%value(i, jj) - kd)/kmax)
                end do
            end do
        end do
        call report("largest |K_d - 2 (1 - nu^2) C/|q||/max|K_d|", worst)
        call check(error, worst <= 1.0e-13_dp, "the 200-term kernel differs from its compliance")
    contains
        complex(dp) function quad_compliance(w) result(c)
            real(dp), intent(in) :: w
            complex(qp) :: s
            integer :: jt
            s = cmplx(1.0e6_qp, 0.0_qp, qp)
            do jt = 1, n
                s = s + e(jt)*cmplx(0.0_qp, w*real(tau_j(jt), qp), qp)/cmplx(1.0_qp, w*real(tau_j(jt), qp), qp)
            end do
            c = cmplx(1.0_qp/s, kind=dp)
        end function quad_compliance
    end subroutine test_long_series

    !> x = resolvent(z) solves x + gamma s K x = z + gamma r on every mode but the mean, which is set
    subroutine test_resolvent(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 16
        real(dp), parameter :: gamma = 0.7_dp, s = 3.0e6_dp
        type(material_t) :: m
        type(kernel_t), target :: k
        type(resolvent_t) :: res
        type(fft2d_t), target :: fft
        type(transform_t) :: t
        type(carray_t) :: kd, rka
        real(dp) :: z(n, n), r(n, n), x(n, n), kx(n, n), lhs(n, n), rhs(n, n)
        complex(dp), allocatable, target :: rk(:, :)
        call paper_solid(100.0_dp, m, error); if (allocated(error)) return
        call new_kernel(k, cell_grid(n, n), m, peak_speed(100.0_dp, 3.0_dp)*[cos(1.0_dp), sin(1.0_dp)], &
                        KERNEL_SPECTRAL, error)
        if (allocated(error)) return
        call fft%init(n, n, error, planner='estimate'); if (allocated(error)) return
        call random_number(z); call random_number(r)
        fft%x = r; call fft%forward(); rk = fft%k
        call k%multiplier_array(kd, .false.)
        call res%set(kd, gamma, s, k%grid%cells(), owns_mean=.true.)
        call t%on_host(fft)
        call rka%view(rk)
        fft%x = z
        call res%solve(t, rka, gamma, 0.25_dp)
        x = fft%x
        call k%apply(fft, x, kx)
        lhs = x + gamma*s*kx; rhs = z + gamma*r
        lhs = lhs - sum(lhs)/size(lhs); rhs = rhs - sum(rhs)/size(rhs)
        call report("max |(I + g s K) x - (z + g r)|", maxval(abs(lhs - rhs))/maxval(abs(rhs)))
        call check(error, maxval(abs(lhs - rhs)) <= 1.0e-12_dp*maxval(abs(rhs)), "resolvent does not invert")
        if (allocated(error)) return
        call check(error, sum(x)/size(x), 0.25_dp, "mean of x", rel=1.0e-13_dp)
    end subroutine test_resolvent

    !> A multiplier with a negative real part somewhere is refused
    subroutine test_from_multiplier(error)
        type(error_t), allocatable, intent(out) :: error
        complex(dp) :: kd(5, 8)
        type(kernel_t) :: k
        kd = (1.0_dp, 0.0_dp); kd(3, 4) = (-1.0e-3_dp, 0.0_dp)
        call new_kernel_from_multiplier(k, cell_grid(8, 8), kd, [0.0_dp, 0.0_dp], error)
    end subroutine test_from_multiplier

    !> An interfacial shear mu_f p v_hat on the solid multiplies the kernel of every mode by
    !> 1 - i beta mu_f (q.v_hat)/|q|, beta = (1 - 2 nu)/(2 (1 - nu)) (docs/interface.md): the
    !> spectral kernel with shear against 2 (1 - nu^2) C(-q.v) (1 - i beta mu_f (q.v_hat)/|q|)/|q|
    !> written here, the two signs of a Nyquist line averaged, mode by mode within 1e-14 of the
    !> mode's own |K| (one rounding of the factor's product; measured below 3e-16). A one-term
    !> solid (nu = 0.3, beta = 2/7) sliding at 30 degrees, and an elastic one (nu = 0.1) at rest
    !> sheared along y, on a 16 x 12 grid (both Nyquist lines).
    subroutine test_shear_multiplier(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: nx = 16, ny = 12
        real(dp), parameter :: mu_f = 0.7_dp
        type(material_t) :: m
        type(kernel_t) :: k
        type(grid_t) :: grid
        real(dp) :: v(2), vhat(2), nu, beta, worst
        integer :: which
        grid = cell_grid(nx, ny)
        worst = 0.0_dp
        do which = 1, 2
            if (which == 1) then
                nu = 0.3_dp; beta = 0.4_dp/1.4_dp
                call new_one_term(m, einf, 11.0_dp, tau, nu, error); if (allocated(error)) return
                vhat = [cos(pi/6), sin(pi/6)]; v = peak_speed(11.0_dp, 2.0_dp)*vhat
            else
                nu = 0.1_dp; beta = 0.8_dp/1.8_dp
                call new_elastic(m, 3.0e6_dp, nu, error); if (allocated(error)) return
                vhat = [0.0_dp, 1.0_dp]; v = 0.0_dp
            end if
            call new_kernel(k, grid, m, v, KERNEL_SPECTRAL, error, shear=mu_f*vhat); if (allocated(error)) return
            worst = max(worst, deviation())
        end do
        call report("largest |K_d - K (1 - i beta mu_f q.v_hat/|q|)|/|K|", worst)
        call check(error, worst <= 1.0e-14_dp, "the kernel with shear is not the factor times the kernel")
    contains
        real(dp) function deviation() result(w)
            real(dp) :: q(2)
            complex(dp) :: kd
            integer :: i, j, rx, ry, nrx, nry
            w = 0.0_dp
            do j = 1, ny
                do i = 1, nx/2 + 1
                    if (i == 1 .and. j == 1) cycle
                    nrx = merge(2, 1, grid%is_nyquist_x(i)); nry = merge(2, 1, grid%is_nyquist_y(j))
                    kd = (0.0_dp, 0.0_dp)
                    do ry = 1, nry
                        do rx = 1, nrx
                            q = grid%wavevector(i, j)
                            if (rx == 2) q(1) = -q(1)
                            if (ry == 2) q(2) = -q(2)
                            kd = kd + 2.0_dp*(1.0_dp - nu**2)*m%compliance(-dot_product(q, v))/norm2(q) &
                                 *cmplx(1.0_dp, -beta*mu_f*dot_product(q, vhat)/norm2(q), dp)
                        end do
                    end do
                    kd = kd/(nrx*nry)
                    w = max(w, abs(k%value(i, j) - kd)/abs(kd))
                end do
            end do
        end function deviation
    end subroutine test_shear_multiplier

    !> The non-symmetric solvers need Re K > 0 on every mode. With shear Re K is
    !> Re C + beta mu_f (q.v_hat)/|q| Im C(-q.v) (times 2 (1 - nu^2)/|q|), and Im C(w) has the
    !> sign of -w = q.v for a passive solid: the coupling never lowers Re K (docs/interface.md).
    !> Mode by mode for a one-term solid (Einf/E0 = 100, nu = 0.2) sliding at 20 degrees with
    !> mu_f = 2; strictly higher on the modes it reaches.
    subroutine test_shear_re_k(error)
        type(error_t), allocatable, intent(out) :: error
        integer, parameter :: n = 16
        type(material_t) :: m
        type(kernel_t) :: k0, k1
        real(dp) :: vhat(2)
        integer :: i, j, raised
        call new_one_term(m, einf, 100.0_dp, tau, 0.2_dp, error); if (allocated(error)) return
        vhat = [cos(pi/9), sin(pi/9)]
        call new_kernel(k0, cell_grid(n, n), m, peak_speed(100.0_dp, 3.0_dp)*vhat, KERNEL_SPECTRAL, error)
        if (allocated(error)) return
        call new_kernel(k1, cell_grid(n, n), m, peak_speed(100.0_dp, 3.0_dp)*vhat, KERNEL_SPECTRAL, error, &
                        shear=2.0_dp*vhat)
        if (allocated(error)) return
        raised = 0
        do j = 1, n
            do i = 1, n/2 + 1
                if (i == 1 .and. j == 1) cycle
                call check(error, real(k1%value(i, j), dp) >= real(k0%value(i, j), dp), "shear lowered Re K")
                if (allocated(error)) return
                if (real(k1%value(i, j), dp) > real(k0%value(i, j), dp)) raised = raised + 1
            end do
        end do
        call report("modes whose Re K the shear raised", real(raised, dp))
        call check(error, raised > n*n/4 .and. k1%min_re >= k0%min_re, "shear did not raise Re K")
    end subroutine test_shear_re_k

    !> With shear the kernel is not symmetric even for an elastic solid at rest (its flag tells the
    !> solvers), and it is at nu = 1/2 (beta = 0: the very kernel without shear, bit for bit)
    subroutine test_shear_symmetry(error)
        type(error_t), allocatable, intent(out) :: error
        type(material_t) :: m
        type(kernel_t) :: k0, k1
        type(fft2d_t) :: fft
        real(dp) :: p(16, 16), f(2)
        call new_elastic(m, 1.0e7_dp, 0.3_dp, error); if (allocated(error)) return
        call new_kernel(k1, cell_grid(16, 16), m, [0.0_dp, 0.0_dp], KERNEL_SPECTRAL, error, shear=[0.5_dp, 0.0_dp])
        if (allocated(error)) return
        call check(error, .not. k1%symmetric, "an elastic kernel with shear is not symmetric")
        if (allocated(error)) return
        call fft%init(16, 16, error, planner='estimate'); if (allocated(error)) return
        call random_number(p)
        f = k1%tangential_force(fft, p)
        call check(error, abs(f(1)) > 0.0_dp, "an elastic kernel with shear has a tangential force")
        if (allocated(error)) return
        call new_elastic(m, 1.0e7_dp, 0.5_dp, error); if (allocated(error)) return
        call new_kernel(k0, cell_grid(16, 16), m, [0.0_dp, 0.0_dp], KERNEL_SPECTRAL, error); if (allocated(error)) return
        call new_kernel(k1, cell_grid(16, 16), m, [0.0_dp, 0.0_dp], KERNEL_SPECTRAL, error, shear=[0.5_dp, 0.0_dp])
        if (allocated(error)) return
        call check(error, k1%symmetric .and. all(k1%multiplier(1.0_dp) == k0%multiplier(1.0_dp)), &
                   "at nu = 1/2 the shear changes the kernel")
    end subroutine test_shear_symmetry

    !> A layer's coupling is not the half-space's beta: refused, at any nu
    subroutine test_shear_layer(error)
        type(error_t), allocatable, intent(out) :: error
        type(material_t) :: m
        type(kernel_t) :: k
        call new_elastic(m, 1.0e7_dp, 0.5_dp, error); if (allocated(error)) return
        m%thickness_m = 1.0e-3_dp
        call new_kernel(k, cell_grid(8, 8), m, [0.0_dp, 0.0_dp], KERNEL_SPECTRAL, error, shear=[0.3_dp, 0.0_dp])
    end subroutine test_shear_layer

    !> The discrete check min Re K_d > 0 stays the guard with shear, in one line: the case where
    !> collocation-alias loses definiteness (Einf/E0 = 1000 at 15 degrees) with a shear along v
    subroutine test_shear_definiteness(error)
        type(error_t), allocatable, intent(out) :: error
        type(material_t) :: m
        type(kernel_t) :: k
        call new_one_term(m, einf, 1000.0_dp, tau, 0.3_dp, error); if (allocated(error)) return
        call new_kernel(k, cell_grid(32, 32), m, lcell/tau*[cos(pi/12), sin(pi/12)], KERNEL_COLLOCATION_ALIAS, &
                        error, alias_tol=1.0e-4_dp, shear=0.5_dp*[cos(pi/12), sin(pi/12)])
    end subroutine test_shear_definiteness

end module test_veslide_kernel
