!> Periodic influence operator of a half-space, applied as a Fourier multiplier on the r2c
!> half-spectrum: the kernel as an operator.
!>
!> Displacement from pressure in the sliding frame: w(q) = K(q) p(q), K(q) = 2(1-nu^2) C(-q.v)/|q|,
!> C the complex compliance of the material (elastic: C = 1/E). With an interfacial shear
!> traction mu_f p v_hat on the solid (full-slip Coulomb friction, `shear` = mu_f v_hat) the
!> half-space's normal displacement gains the Cerruti part, and K(q) is multiplied by
!> 1 - i beta mu_f (q.v_hat)/|q|, beta = (1 - 2 nu)/(2 (1 - nu)) (docs/interface.md; a layer
!> with shear is refused: its coupling is another function of q d). On the grid the multiplier is
!>   K_d(q_k) = sum_m K(q_k + Q m) S(q_k + Q m),   Q = (2 pi/a, 2 pi/b)
!> with, per variant,
!>   spectral:    m = 0 only, S = 1 (what most FFT contact codes do);
!>   collocation: m = 0 only, S = sinc(qx a/2) sinc(qy b/2) (uniform pressure on the cell, point receiver);
!>   collocation-alias: S as collocation, summed over alias zones (the exact real-space influence
!>                coefficients of the paper's eq. 10, periodised);
!>   galerkin:    S = sinc^2 (cell-averaged source and receiver), summed over alias zones.
!> Alias sums run over square shells |m|_inf <= M, M = 2, 4, 8, ..., with Richardson extrapolation
!> (error ~ M^-2); they stop when the extrapolated value changes by less than `alias_tol` relative to
!> max|K_d|, and report the estimate. One code path serves elastic and viscoelastic kernels.
!> The q = 0 mode is zero: the mean displacement is the rigid-body approach of the solver.
!>
!> What the solvers and the analysis use (they never touch the multiplier or the FFT themselves):
!>  - `apply`:  out = K f (zero mean); `apply_buffer`: the same in place on an FFT buffer;
!>  - `impulse_response`: K applied to a unit pressure on cell (1, 1) (one column of the matrix);
!>  - `resolvent_t`: the multiplier of (I + gamma s K)^-1 (`set` from K_d), whose `solve` gives
!>    x = (I + gamma s K)^-1 (z + gamma r) with the mean of x fixed, on the host or the device
!>    (its two passes in veslide_kernel_passes);
!>  - `multiplier_array`: K_d where a solve runs (a view on the host, a copy on the device);
!>  - `tangential_force`: F = <p grad w> of a pressure field, exact for the discrete operator;
!>  - `multiplier`: s K_d/(nx ny), for solvers that build operators of their own from it (the
!>    symmetric part or the modulus as a metric, their inverses as preconditioners);
!>  - `modulus_spread`: the largest max/min of |K_d| |q| within one shell of |q|: the operator's
!>    anisotropy (1 for an elastic solid; up to Einf/E0 for a viscoelastic one in motion).
module veslide_kernel
    use veslide_kinds, only: dp, two_pi
    use veslide_error, only: error_t, fatal_error, ERROR_NUMERICAL
    use veslide_strings, only: name_index
    use veslide_grid, only: grid_t
    use veslide_fftw, only: fft2d_t
    use veslide_collective, only: ordered_sum, global_min, global_max, global_any
    use veslide_material, only: material_t, coupling_beta
    use veslide_arrays, only: carray_t
    use veslide_transform, only: transform_t
    use veslide_kernel_passes, only: resolvent_multiplier, resolvent_apply
    implicit none
    private
    public :: kernel_t, resolvent_t, new_kernel, new_kernel_from_multiplier, kernel_variant_id, kernel_names
    public :: KERNEL_SPECTRAL, KERNEL_COLLOCATION, KERNEL_COLLOCATION_ALIAS, KERNEL_GALERKIN

    integer, parameter :: KERNEL_SPECTRAL = 1, KERNEL_COLLOCATION = 2, &
                          KERNEL_COLLOCATION_ALIAS = 3, KERNEL_GALERKIN = 4
    !> Names of the variants, indexed by their KERNEL_* id (the namelist's `&solver kernel`)
    character(len=*), parameter :: kernel_names(4) = [character(len=17) :: 'spectral', 'collocation', &
                                                      'collocation-alias', 'galerkin']

    !> The discrete influence operator of one grid, material, velocity and variant
    type :: kernel_t
        type(grid_t) :: grid                         !! the grid it acts on
        integer :: variant = KERNEL_SPECTRAL         !! KERNEL_* id
        real(dp) :: velocity_m_s(2) = 0.0_dp         !! sliding velocity of the rigid surface [m/s]
        !> interfacial shear traction on the solid per unit contact pressure, mu_f v_hat [-] (0: none)
        real(dp) :: shear(2) = 0.0_dp
        logical :: symmetric = .true.                !! all Im K_d == 0 (elastic or v = 0): a symmetric operator
        integer :: alias_zones = 0                   !! M of the last shell summed (0: none)
        real(dp) :: alias_error = 0.0_dp             !! estimated relative error of the alias sum
        real(dp) :: min_re = 0.0_dp                  !! min Re K_d over q /= 0 [m/Pa]
        complex(dp), allocatable, private :: kd(:, :)  !! multiplier K_d on the grid's spectral storage [m/Pa]
    contains
        procedure :: apply => kernel_apply
        procedure :: apply_buffer => kernel_apply_buffer
        procedure :: impulse_response => kernel_impulse_response
        procedure :: tangential_force => kernel_tangential_force
        procedure :: value => kernel_value
        procedure :: multiplier => kernel_multiplier
        procedure :: modulus_spread => kernel_modulus_spread
        procedure :: max_abs => kernel_max_abs
        procedure :: typical_abs => kernel_typical_abs
        procedure :: move_to => kernel_move_to
        procedure :: multiplier_array => kernel_multiplier_array
    end type kernel_t

    !> The multiplier of (I + gamma s K)^-1 / (nx ny) (FFTW's normalisation folded in), held
    !> where the K_d it is made from is
    type :: resolvent_t
        type(carray_t) :: mult
        logical, private :: owns_mean = .true.     !! this process holds q = 0
    contains
        procedure :: set => resolvent_set
        procedure :: solve => resolvent_solve
        procedure :: destroy => resolvent_destroy
    end type resolvent_t

contains

    !> KERNEL_* id from a variant name; 0 when unknown
    pure integer function kernel_variant_id(name) result(id)
        character(len=*), intent(in) :: name
        id = name_index(name, kernel_names)
    end function kernel_variant_id

    elemental real(dp) function sinc(z)
        real(dp), intent(in) :: z
        if (abs(z) < 1.0e-8_dp) then
            sinc = 1.0_dp - z*z/6.0_dp
        else
            sinc = sin(z)/z
        end if
    end function sinc

    !> Continuous kernel 2(1-nu^2) C(-q.v) S(|q| d)/|q| (S: a layer's factor, 1 for a half-space),
    !> times 1 - i (q.cpl)/|q| with an interfacial shear (cpl = beta mu_f v_hat; skipped when 0,
    !> so the kernel without shear is the same bit for bit), times the cell factor of the
    !> variant; `comp`: C(-q.v) when the caller has it
    pure complex(dp) function term(mat, q, v, cpl, a, b, variant, comp) result(t)
        type(material_t), intent(in) :: mat
        real(dp), intent(in) :: q(2), v(2), cpl(2), a, b
        integer, intent(in) :: variant
        complex(dp), intent(in), optional :: comp
        real(dp) :: s, qn
        complex(dp) :: c
        qn = norm2(q)
        if (present(comp)) then
            c = comp
        else
            c = mat%compliance(-dot_product(q, v))
        end if
        t = 2.0_dp*(1.0_dp - mat%poisson**2)*c*mat%layer(qn)/qn
        if (cpl(1) /= 0.0_dp .or. cpl(2) /= 0.0_dp) t = t*cmplx(1.0_dp, -dot_product(q, cpl)/qn, dp)
        select case (variant)
        case (KERNEL_COLLOCATION, KERNEL_COLLOCATION_ALIAS)
            s = sinc(0.5_dp*q(1)*a)*sinc(0.5_dp*q(2)*b)
            t = t*s
        case (KERNEL_GALERKIN)
            s = sinc(0.5_dp*q(1)*a)*sinc(0.5_dp*q(2)*b)
            t = t*s*s
        end select
    end function term

    !> Sum of term() over the shell |m|_inf == m (m = 0: the single term m = 0)
    pure complex(dp) function shell_sum(mat, q, v, cpl, a, b, variant, m, use_x, use_y) result(s)
        type(material_t), intent(in) :: mat
        real(dp), intent(in) :: q(2), v(2), cpl(2), a, b
        integer, intent(in) :: variant, m
        logical, intent(in) :: use_x, use_y   ! a direction with one cell has no aliases
        real(dp) :: bq(2)
        integer :: mx, my
        bq = [two_pi/a, two_pi/b]
        s = (0.0_dp, 0.0_dp)
        if (m == 0) then
            s = term(mat, q, v, cpl, a, b, variant); return
        end if
        if (use_x .and. use_y) then
            do my = -m, m
                if (abs(my) == m) then
                    do mx = -m, m
                        s = s + term(mat, q + bq*[mx, my], v, cpl, a, b, variant)
                    end do
                else
                    s = s + term(mat, q + bq*[-m, my], v, cpl, a, b, variant)
                    s = s + term(mat, q + bq*[m, my], v, cpl, a, b, variant)
                end if
            end do
        else if (use_x) then
            s = term(mat, q + bq*[-m, 0], v, cpl, a, b, variant) + term(mat, q + bq*[m, 0], v, cpl, a, b, variant)
        else if (use_y) then
            s = term(mat, q + bq*[0, -m], v, cpl, a, b, variant) + term(mat, q + bq*[0, m], v, cpl, a, b, variant)
        end if
    end function shell_sum

    !> Build the operator for a grid, material, velocity and variant (and an interfacial shear)
    subroutine new_kernel(self, grid, mat, velocity_m_s, variant, error, alias_tol, alias_max, shear)
        type(kernel_t), intent(out) :: self
        type(grid_t), intent(in) :: grid
        type(material_t), intent(in) :: mat
        !> velocity of the rigid surface relative to the solid [m/s]
        real(dp), intent(in) :: velocity_m_s(2)
        !> KERNEL_* id
        integer, intent(in) :: variant
        type(error_t), allocatable, intent(out) :: error
        !> relative tolerance of the alias sums (default 1e-6)
        real(dp), intent(in), optional :: alias_tol
        !> largest shell index M (default 64)
        integer, intent(in), optional :: alias_max
        !> interfacial shear traction on the solid per unit contact pressure, mu_f v_hat [-], v_hat
        !> the direction of the rigid surface's velocity (full-slip Coulomb friction; default none)
        real(dp), intent(in), optional :: shear(2)
        real(dp) :: tol_, a, b, kmax, worst, d(2), cpl(2)
        integer :: max_, i, j, m, nrep_x, nrep_y, rx, ry, nx, ny, na, nb, ia, ib, ij(2), sh(2)
        real(dp) :: q(2), qr(2)
        complex(dp), allocatable :: s_prev(:, :), r_prev(:, :), s_cur(:, :), r_cur(:, :)
        ! C(-q.v) depends on q only through q.v: with v along x (or zero) it takes one value per
        ! column of the spectrum, with v along y one per row, tabulated once for shell 0 (signed
        ! twice for the Nyquist lines) and the same value bit for bit (q.v = q_x v_x + q_y 0):
        ! a long Prony series then costs its terms per column, not per mode
        complex(dp), allocatable :: c_line(:, :)
        logical :: use_x, use_y, aliased, along_x, along_y

        tol_ = 1.0e-6_dp; if (present(alias_tol)) tol_ = alias_tol
        max_ = 64; if (present(alias_max)) max_ = alias_max
        nx = grid%nx; ny = grid%ny
        if (nx < 1 .or. ny < 1 .or. .not. (grid%lx_m > 0.0_dp .and. grid%ly_m > 0.0_dp)) then
            call fatal_error(error, "veslide:kernel:new_kernel: grid and cell size must be positive"); return
        end if
        if (variant < 1 .or. variant > size(kernel_names)) then
            call fatal_error(error, "veslide:kernel:new_kernel: unknown kernel variant"); return
        end if
        if (present(shear)) self%shear = shear
        if (any(self%shear /= 0.0_dp) .and. mat%thickness_m > 0.0_dp) then
            call fatal_error(error, "veslide:kernel:new_kernel: an interfacial shear on a layer is not"// &
                             " available (the layer's normal-tangential coupling is not beta; docs/interface.md)")
            return
        end if
        cpl = coupling_beta(mat%poisson)*self%shear
        self%grid = grid
        self%variant = variant; self%velocity_m_s = velocity_m_s
        d = grid%spacing(); a = d(1); b = d(2)
        use_x = nx > 1; use_y = ny > 1
        aliased = variant == KERNEL_COLLOCATION_ALIAS .or. variant == KERNEL_GALERKIN
        sh = grid%spectral_shape(); na = sh(1); nb = sh(2)
        allocate (self%kd(na, nb))
        along_x = velocity_m_s(2) == 0.0_dp; along_y = velocity_m_s(1) == 0.0_dp .and. .not. along_x
        if (along_x) then
            allocate (c_line(nx/2 + 1, 2))
            do i = 1, nx/2 + 1
                q = grid%wavevector(i, 1)
                c_line(i, 1) = mat%compliance(-dot_product(q, velocity_m_s))
                c_line(i, 2) = mat%compliance(-dot_product([-q(1), q(2)], velocity_m_s))
            end do
        else if (along_y) then
            allocate (c_line(ny, 2))
            do j = 1, ny
                q = grid%wavevector(1, j)
                c_line(j, 1) = mat%compliance(-dot_product(q, velocity_m_s))
                c_line(j, 2) = mat%compliance(-dot_product([q(1), -q(2)], velocity_m_s))
            end do
        end if

        ! Shell 0, then shells 1..M in doubling stages. On a Nyquist line the two signed
        ! representatives of the mode are averaged (this keeps the operator real, and makes
        ! truncated alias sums symmetric).
        ! (Without aliases shell 0 is the multiplier, summed in place: the stages' arrays, each
        ! as large, are neither allocated nor touched, nor copied.)
        m = 0
        if (.not. aliased) then
            call add_shells(0, 0, self%kd)
        else
            allocate (s_cur(na, nb), r_cur(na, nb), s_prev(na, nb), r_prev(na, nb))
            call add_shells(0, 0, s_cur)
            r_prev = s_cur
            m = 1
            call add_shells(1, 1, s_cur)
            do
                s_prev = s_cur
                call add_shells(m + 1, 2*m, s_cur)
                m = 2*m
                ! Richardson for an M^-2 tail: R(M) = S(M) + (S(M) - S(M/2))/3
                r_cur = s_cur + (s_cur - s_prev)/3.0_dp
                ! (every process takes the same decision: global extrema)
                kmax = maxval(abs(r_cur)); call global_max(grid, kmax)
                worst = 0.0_dp; if (size(r_cur) > 0) worst = maxval(abs(r_cur - r_prev))
                call global_max(grid, worst)
                worst = worst/kmax
                r_prev = r_cur
                if (worst <= tol_ .or. 2*m > max_) exit
            end do
            self%kd = r_cur
            self%alias_zones = m
            self%alias_error = worst
        end if
        call finish_kernel(self, error)

    contains

        subroutine add_shells(m1, m2, acc)
            integer, intent(in) :: m1, m2
            complex(dp), intent(inout) :: acc(:, :)
            integer :: mm
            complex(dp) :: s
            if (m1 == 0) acc = (0.0_dp, 0.0_dp)
            !$omp parallel do schedule(dynamic) private(ia, i, j, ij, q, qr, nrep_x, nrep_y, rx, ry, s, mm)
            do ib = 1, nb
                do ia = 1, na
                    ij = grid%spectral_index(ia, ib); i = ij(1); j = ij(2)
                    if (i == 1 .and. j == 1) cycle
                    q = grid%wavevector(i, j)
                    nrep_x = merge(2, 1, grid%is_nyquist_x(i)); nrep_y = merge(2, 1, grid%is_nyquist_y(j))
                    s = (0.0_dp, 0.0_dp)
                    do ry = 1, nrep_y
                        do rx = 1, nrep_x
                            qr = q
                            if (rx == 2) qr(1) = -qr(1)
                            if (ry == 2) qr(2) = -qr(2)
                            do mm = m1, m2
                                if (mm == 0 .and. along_x) then
                                    s = s + term(mat, qr, velocity_m_s, cpl, a, b, variant, c_line(i, rx))
                                else if (mm == 0 .and. along_y) then
                                    s = s + term(mat, qr, velocity_m_s, cpl, a, b, variant, c_line(j, ry))
                                else
                                    s = s + shell_sum(mat, qr, velocity_m_s, cpl, a, b, variant, mm, use_x, use_y)
                                end if
                            end do
                        end do
                    end do
                    acc(ia, ib) = acc(ia, ib) + s/real(nrep_x*nrep_y, dp)
                end do
            end do
            !$omp end parallel do
        end subroutine add_shells

    end subroutine new_kernel

    !> K_d [m/Pa] on the grid's spectral storage where a solve runs: a view of the kernel's own on
    !> the host (the kernel must outlive it), a copy on the device
    subroutine kernel_multiplier_array(self, kd, device)
        class(kernel_t), intent(in), target :: self
        type(carray_t), intent(inout) :: kd
        logical, intent(in) :: device
        if (device) then
            call kd%create(size(self%kd, 1), size(self%kd, 2), .true.)
            call kd%upload(self%kd)
        else
            call kd%view(self%kd)
        end if
    end subroutine kernel_multiplier_array

    !> Hand the operator to `dest` without copying its multiplier; `self` is left without one
    subroutine kernel_move_to(self, dest)
        class(kernel_t), intent(inout) :: self
        type(kernel_t), intent(out) :: dest
        complex(dp), allocatable :: kd(:, :)
        call move_alloc(self%kd, kd)
        select type (self)
        type is (kernel_t)
            dest = self
        end select
        call move_alloc(kd, dest%kd)
    end subroutine kernel_move_to

    !> A kernel from a given multiplier K_d on the half-spectrum of `grid`, in the grid's spectral
    !> storage (a material law or a geometry that new_kernel does not build: layered solids,
    !> tabulated compliances, limits)
    subroutine new_kernel_from_multiplier(self, grid, kd, velocity_m_s, error)
        type(kernel_t), intent(out) :: self
        type(grid_t), intent(in) :: grid
        complex(dp), intent(in) :: kd(:, :)
        real(dp), intent(in) :: velocity_m_s(2)
        type(error_t), allocatable, intent(out) :: error
        if (any(shape(kd) /= grid%spectral_shape())) then
            call fatal_error(error, "veslide:kernel:new_kernel_from_multiplier: the multiplier is not"// &
                             " on the grid's spectral storage ((nx/2+1, ny) on one process)")
            return
        end if
        self%grid = grid; self%velocity_m_s = velocity_m_s; self%variant = 0
        self%kd = kd
        call finish_kernel(self, error)
    end subroutine new_kernel_from_multiplier

    !> Zero mean mode, symmetry flag, and the definiteness check min Re K_d > 0
    subroutine finish_kernel(self, error)
        type(kernel_t), intent(inout) :: self
        type(error_t), allocatable, intent(out) :: error
        integer :: i, j
        logical :: skewed, nan
        if (self%grid%owns_mean_mode()) self%kd(1, 1) = (0.0_dp, 0.0_dp)
        skewed = any(aimag(self%kd) /= 0.0_dp)
        call global_any(self%grid, skewed)
        self%symmetric = .not. skewed
        self%min_re = huge(1.0_dp); nan = .false.
        do j = 1, size(self%kd, 2)
            do i = 1, size(self%kd, 1)
                if (i == 1 .and. j == 1 .and. self%grid%owns_mean_mode()) cycle
                nan = nan .or. real(self%kd(i, j), dp) /= real(self%kd(i, j), dp)
                self%min_re = min(self%min_re, real(self%kd(i, j), dp))
            end do
        end do
        if (nan) self%min_re = -huge(1.0_dp)      ! not finite: refused below
        call global_min(self%grid, self%min_re)
        if (self%grid%cells() == 1.0_dp) self%min_re = 0.0_dp
        if (.not. (self%min_re > 0.0_dp) .and. self%grid%cells() > 1.0_dp) then
            if (self%variant == KERNEL_COLLOCATION_ALIAS) then
                call fatal_error(error, "veslide:kernel:new_kernel: the discrete kernel is not positive definite"// &
                    " (min Re K_d <= 0); the collocation-alias variant loses definiteness for large"// &
                    " Einf/E0 at speed: use the 'galerkin' or 'collocation' variant", ERROR_NUMERICAL)
            else
                call fatal_error(error, "veslide:kernel:new_kernel: the discrete kernel is not positive definite"// &
                    " (min Re K_d <= 0, or not finite)", ERROR_NUMERICAL)
            end if
        end if
    end subroutine finish_kernel

    !> out = K f (zero mean), using the buffers of `fft`
    subroutine kernel_apply(self, fft, f, out)
        class(kernel_t), intent(in) :: self
        type(fft2d_t), intent(inout) :: fft
        real(dp), intent(in) :: f(:, :)
        real(dp), intent(out) :: out(:, :)
        fft%x = f
        call self%apply_buffer(fft)
        out = fft%x
    end subroutine kernel_apply

    !> fft%x <- K fft%x in place (one FFT pair; fft%k is overwritten)
    subroutine kernel_apply_buffer(self, fft)
        class(kernel_t), intent(in) :: self
        type(fft2d_t), intent(inout) :: fft
        real(dp) :: inv_n
        integer :: i, j
        inv_n = 1.0_dp/self%grid%cells()
        call fft%forward()
        ! one fused pass (an array expression here made a temporary of K_d/N on every call)
        do j = 1, size(fft%k, 2)
            do i = 1, size(fft%k, 1)
                fft%k(i, j) = fft%k(i, j)*(self%kd(i, j)*inv_n)
            end do
        end do
        call fft%backward_unscaled()
    end subroutine kernel_apply_buffer

    !> green = K applied to a unit pressure on cell (1, 1); column j of the influence matrix is
    !> green shifted periodically to cell j
    subroutine kernel_impulse_response(self, fft, green)
        class(kernel_t), intent(in) :: self
        type(fft2d_t), intent(inout) :: fft
        real(dp), intent(out) :: green(:, :)
        fft%k = self%kd/self%grid%cells()
        call fft%backward_unscaled()
        green = fft%x
    end subroutine kernel_impulse_response

    !> The resolvent (I + gamma s K)^-1 as a multiplier (s scales K, e.g. to dimensionless
    !> units), from K_d as `kd` holds it (host or device) on a grid of `cells` cells
    subroutine resolvent_set(self, kd, gamma, s, cells, owns_mean)
        class(resolvent_t), intent(inout) :: self
        type(carray_t), intent(in) :: kd
        real(dp), intent(in) :: gamma, s, cells
        logical, intent(in) :: owns_mean    !! this process holds q = 0
        if (self%mult%n1 /= kd%n1 .or. self%mult%n2 /= kd%n2 .or. (self%mult%device .neqv. kd%device)) &
            call self%mult%create(kd%n1, kd%n2, kd%device)
        call resolvent_multiplier(self%mult, kd, gamma, s, cells)
        self%owns_mean = owns_mean
    end subroutine resolvent_set

    !> x = (I + gamma s K)^-1 (z + gamma r) with mean(x) = mean_x: on entry t%x holds z and
    !> `rk` the unnormalised transform of r; on exit t%x holds x (one FFT pair)
    subroutine resolvent_solve(self, t, rk, gamma, mean_x)
        class(resolvent_t), intent(in) :: self
        type(transform_t), intent(inout) :: t
        type(carray_t), intent(in) :: rk
        real(dp), intent(in) :: gamma, mean_x
        call t%forward()
        call resolvent_apply(t%k, self%mult, rk, gamma, self%owns_mean, mean_x)
        call t%backward_unscaled()
    end subroutine resolvent_solve

    subroutine resolvent_destroy(self)
        class(resolvent_t), intent(inout) :: self
        call self%mult%destroy()
    end subroutine resolvent_destroy

    !> Tangential force per unit nominal area exerted by the solid on the rigid surface,
    !> F = <p grad w> [Pa], evaluated exactly for the discrete operator:
    !> F = -(1/N^2) sum_q q Im K_d(q) |P(q)|^2 (full-plane sum, Nyquist lines carry no derivative).
    !> Zero for a symmetric (elastic) kernel.
    function kernel_tangential_force(self, fft, p) result(f)
        class(kernel_t), intent(in) :: self
        type(fft2d_t), intent(inout) :: fft
        real(dp), intent(in) :: p(:, :)
        real(dp) :: f(2)
        real(dp), allocatable :: cols(:, :)
        integer :: a, b, ij(2)
        f = 0.0_dp
        if (self%symmetric) return
        fft%x = p
        call fft%forward()
        allocate (cols(2, size(fft%k, 2)))
        !$omp parallel do schedule(guided) private(a, ij)
        do b = 1, size(fft%k, 2)
            cols(:, b) = 0.0_dp
            do a = 1, size(fft%k, 1)
                ij = self%grid%spectral_index(a, b)
                cols(:, b) = cols(:, b) - self%grid%hermitian_weight(ij(1)) &
                             *self%grid%derivative_wavevector(ij(1), ij(2))*aimag(self%kd(a, b))*abs(fft%k(a, b))**2
            end do
        end do
        !$omp end parallel do
        call ordered_sum(self%grid, cols, f, spectral=.true.)
        f = f/self%grid%cells()**2
    end function kernel_tangential_force

    !> K_d at storage position (i, j) of the grid's half-spectrum (the entry (i, j) on one
    !> process; `grid%spectral_index` maps positions to entries on a distributed grid) [m/Pa]
    elemental complex(dp) function kernel_value(self, i, j) result(k)
        class(kernel_t), intent(in) :: self
        integer, intent(in) :: i, j
        k = self%kd(i, j)
    end function kernel_value

    !> s K_d/(nx ny) on the grid's spectral storage (`grid%spectral_shape()`: the half-spectrum
    !> (nx/2+1, ny), or this process's transposed share), FFTW's normalisation folded in [s m/Pa]
    pure function kernel_multiplier(self, s) result(m)
        class(kernel_t), intent(in) :: self
        real(dp), intent(in) :: s
        complex(dp), allocatable :: m(:, :)
        m = self%kd*(s/self%grid%cells())
    end function kernel_multiplier

    !> The largest ratio max/min of |K_d(q)| |q| among the modes of one shell of |q| (shells one
    !> fundamental wavenumber wide): how anisotropic the operator is at a fixed scale. 1 for an
    !> elastic solid (up to the variants' cell factors), up to Einf/E0 for a viscoelastic one in
    !> motion, whose modes along v are glassier than those across it. On a distributed grid the
    !> shells' extremes are taken over all processes (every process gets the same value).
    real(dp) function kernel_modulus_spread(self) result(spread)
        class(kernel_t), intent(in) :: self
        real(dp), allocatable :: lo(:), hi(:)
        real(dp) :: dq, c
        integer :: a, b, k, nshell, ij(2)
        dq = min(two_pi/self%grid%lx_m, two_pi/self%grid%ly_m)
        nshell = nint(norm2(self%grid%wavevector(self%grid%nq(), self%grid%ny/2 + 1))/dq) + 2
        allocate (lo(0:nshell), hi(0:nshell))
        lo = huge(1.0_dp); hi = 0.0_dp
        ! (every mode of the grid, on all threads: on a device's solve, the one pass over the
        ! grid that the host makes; extrema are exact in any order)
        !$omp parallel do schedule(static) private(a, ij, c, k) reduction(min:lo) reduction(max:hi)
        do b = 1, size(self%kd, 2)
            do a = 1, size(self%kd, 1)
                ij = self%grid%spectral_index(a, b)
                if (ij(1) == 1 .and. ij(2) == 1) cycle
                c = norm2(self%grid%wavevector(ij(1), ij(2)))
                k = min(nint(c/dq), nshell)
                c = abs(self%kd(a, b))*c
                lo(k) = min(lo(k), c); hi(k) = max(hi(k), c)
            end do
        end do
        !$omp end parallel do
        call global_min(self%grid, lo)
        call global_max(self%grid, hi)
        spread = 1.0_dp
        do k = 0, nshell
            if (hi(k) > 0.0_dp) spread = max(spread, hi(k)/lo(k))
        end do
    end function kernel_modulus_spread

    !> max |K_d| [m/Pa]
    real(dp) function kernel_max_abs(self) result(k)
        class(kernel_t), intent(in) :: self
        k = maxval(abs(self%kd))
        call global_max(self%grid, k)
    end function kernel_max_abs

    !> Geometric mean of |s K_d| over q /= 0: the magnitude that makes a step of 1/it balanced
    real(dp) function kernel_typical_abs(self, s) result(k)
        class(kernel_t), intent(in) :: self
        real(dp), intent(in) :: s
        real(dp) :: cols(2, size(self%kd, 2)), t(2), v
        integer :: a, b
        do b = 1, size(self%kd, 2)
            cols(:, b) = 0.0_dp
            do a = 1, size(self%kd, 1)
                v = abs(self%kd(a, b)*s)
                if (v > 0.0_dp) cols(:, b) = cols(:, b) + [log(v + tiny(1.0_dp)), 1.0_dp]
            end do
        end do
        call ordered_sum(self%grid, cols, t, spectral=.true.)
        k = exp(t(1)/max(1.0_dp, t(2)))
    end function kernel_typical_abs

end module veslide_kernel
