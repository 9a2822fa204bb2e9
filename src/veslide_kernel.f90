!> Periodic influence operator of a half-space, as a Fourier multiplier on the r2c half-spectrum.
!>
!> Displacement from pressure in the sliding frame: w(q) = K(q) p(q), K(q) = 2(1-nu^2) C(-q.v)/|q|,
!> C the complex compliance of the material (elastic: C = 1/E). On the grid the multiplier is
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
!> The q = 0 mode is set to zero: the mean displacement is the rigid-body approach of the solver.
module veslide_kernel
    use veslide_kinds, only: dp, two_pi
    use veslide_error, only: error_t, fatal_error
    use veslide_material, only: material_t
    implicit none
    private
    public :: kernel_t, build_kernel, wavevector, kernel_variant_id
    public :: KERNEL_SPECTRAL, KERNEL_COLLOCATION, KERNEL_COLLOCATION_ALIAS, KERNEL_GALERKIN

    integer, parameter :: KERNEL_SPECTRAL = 1, KERNEL_COLLOCATION = 2, &
                          KERNEL_COLLOCATION_ALIAS = 3, KERNEL_GALERKIN = 4

    type :: kernel_t
        integer :: nx = 0, ny = 0                    !! grid
        real(dp) :: lx_m = 0.0_dp, ly_m = 0.0_dp     !! cell size [m]
        integer :: variant = KERNEL_SPECTRAL         !! KERNEL_* constant
        real(dp) :: velocity_m_s(2) = 0.0_dp         !! sliding velocity of the rigid surface [m/s]
        complex(dp), allocatable :: kd(:, :)         !! multiplier (nx/2+1, ny) [m/Pa]
        logical :: symmetric = .true.                !! all Im K_d == 0 (elastic or v = 0)
        integer :: alias_zones = 0                   !! M of the last shell summed (0: none)
        real(dp) :: alias_error = 0.0_dp             !! estimated relative error of the alias sum
        real(dp) :: min_re = 0.0_dp                  !! min Re K_d over q /= 0 [m/Pa]
    end type kernel_t

contains

    !> KERNEL_* id from a variant name; 0 when unknown
    integer function kernel_variant_id(name) result(id)
        character(len=*), intent(in) :: name
        select case (trim(name))
        case ('spectral'); id = KERNEL_SPECTRAL
        case ('collocation'); id = KERNEL_COLLOCATION
        case ('collocation-alias'); id = KERNEL_COLLOCATION_ALIAS
        case ('galerkin'); id = KERNEL_GALERKIN
        case default; id = 0
        end select
    end function kernel_variant_id

    !> Wavevector of half-spectrum entry (i, j), 1-based storage indices [1/m]
    pure function wavevector(i, j, nx, ny, lx, ly) result(q)
        integer, intent(in) :: i, j, nx, ny
        real(dp), intent(in) :: lx, ly
        real(dp) :: q(2)
        integer :: jj
        jj = j - 1
        if (jj > ny/2) jj = jj - ny
        q = [two_pi*real(i - 1, dp)/lx, two_pi*real(jj, dp)/ly]
    end function wavevector

    elemental real(dp) function sinc(z)
        real(dp), intent(in) :: z
        if (abs(z) < 1.0e-8_dp) then
            sinc = 1.0_dp - z*z/6.0_dp
        else
            sinc = sin(z)/z
        end if
    end function sinc

    !> Continuous kernel 2(1-nu^2) C(-q.v)/|q| times the cell factor of the variant
    pure complex(dp) function term(mat, q, v, a, b, variant) result(t)
        type(material_t), intent(in) :: mat
        real(dp), intent(in) :: q(2), v(2), a, b
        integer, intent(in) :: variant
        real(dp) :: s, qn
        qn = norm2(q)
        t = 2.0_dp*(1.0_dp - mat%poisson**2)*mat%compliance(-dot_product(q, v))/qn
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
    pure complex(dp) function shell_sum(mat, q, v, a, b, variant, m, use_x, use_y) result(s)
        type(material_t), intent(in) :: mat
        real(dp), intent(in) :: q(2), v(2), a, b
        integer, intent(in) :: variant, m
        logical, intent(in) :: use_x, use_y   ! a direction with one cell has no aliases
        real(dp) :: bq(2)
        integer :: mx, my
        bq = [two_pi/a, two_pi/b]
        s = (0.0_dp, 0.0_dp)
        if (m == 0) then
            s = term(mat, q, v, a, b, variant); return
        end if
        if (use_x .and. use_y) then
            do my = -m, m
                if (abs(my) == m) then
                    do mx = -m, m
                        s = s + term(mat, q + bq*[mx, my], v, a, b, variant)
                    end do
                else
                    s = s + term(mat, q + bq*[-m, my], v, a, b, variant)
                    s = s + term(mat, q + bq*[m, my], v, a, b, variant)
                end if
            end do
        else if (use_x) then
            s = term(mat, q + bq*[-m, 0], v, a, b, variant) + term(mat, q + bq*[m, 0], v, a, b, variant)
        else if (use_y) then
            s = term(mat, q + bq*[0, -m], v, a, b, variant) + term(mat, q + bq*[0, m], v, a, b, variant)
        end if
    end function shell_sum

    !> Build the multiplier for a material, velocity and variant
    subroutine build_kernel(self, nx, ny, lx_m, ly_m, mat, velocity_m_s, variant, error, alias_tol, alias_max)
        type(kernel_t), intent(out) :: self
        integer, intent(in) :: nx, ny
        real(dp), intent(in) :: lx_m, ly_m
        type(material_t), intent(in) :: mat
        !> velocity of the rigid surface relative to the solid [m/s]
        real(dp), intent(in) :: velocity_m_s(2)
        integer, intent(in) :: variant
        type(error_t), allocatable, intent(out) :: error
        !> relative tolerance of the alias sums (default 1e-6)
        real(dp), intent(in), optional :: alias_tol
        !> largest shell index M (default 64)
        integer, intent(in), optional :: alias_max
        real(dp) :: tol_, a, b, kmax, worst
        integer :: max_, i, j, m, nrep_x, nrep_y, rx, ry, nq
        real(dp) :: q(2), qr(2)
        complex(dp), allocatable :: s_prev(:, :), r_prev(:, :), s_cur(:, :), r_cur(:, :)
        logical :: use_x, use_y, nyq_x, nyq_y, aliased

        tol_ = 1.0e-6_dp; if (present(alias_tol)) tol_ = alias_tol
        max_ = 64; if (present(alias_max)) max_ = alias_max
        if (nx < 1 .or. ny < 1 .or. .not. (lx_m > 0.0_dp .and. ly_m > 0.0_dp)) then
            call fatal_error(error, "veslide:kernel:build_kernel: grid and cell size must be positive"); return
        end if
        if (variant < KERNEL_SPECTRAL .or. variant > KERNEL_GALERKIN) then
            call fatal_error(error, "veslide:kernel:build_kernel: unknown kernel variant"); return
        end if
        self%nx = nx; self%ny = ny; self%lx_m = lx_m; self%ly_m = ly_m
        self%variant = variant; self%velocity_m_s = velocity_m_s
        a = lx_m/nx; b = ly_m/ny
        use_x = nx > 1; use_y = ny > 1
        aliased = variant == KERNEL_COLLOCATION_ALIAS .or. variant == KERNEL_GALERKIN
        nq = nx/2 + 1
        allocate (self%kd(nq, ny), s_cur(nq, ny), r_cur(nq, ny))

        ! Shell 0, then shells 1..M in doubling stages. On a Nyquist line the two signed
        ! representatives of the mode are averaged (this keeps the operator real, and makes
        ! truncated alias sums symmetric).
        m = 0
        call add_shells(0, 0, s_cur)
        if (.not. aliased) then
            self%kd = s_cur
        else
            allocate (s_prev(nq, ny), r_prev(nq, ny))
            r_prev = s_cur
            m = 1
            call add_shells(1, 1, s_cur)
            do
                s_prev = s_cur
                call add_shells(m + 1, 2*m, s_cur)
                m = 2*m
                ! Richardson for an M^-2 tail: R(M) = S(M) + (S(M) - S(M/2))/3
                r_cur = s_cur + (s_cur - s_prev)/3.0_dp
                kmax = maxval(abs(r_cur))
                worst = maxval(abs(r_cur - r_prev))/kmax
                r_prev = r_cur
                if (worst <= tol_ .or. 2*m > max_) exit
            end do
            self%kd = r_cur
            self%alias_zones = m
            self%alias_error = worst
        end if
        self%kd(1, 1) = (0.0_dp, 0.0_dp)
        self%symmetric = all(aimag(self%kd) == 0.0_dp)
        self%min_re = huge(1.0_dp)
        do j = 1, ny
            do i = 1, nq
                if (i == 1 .and. j == 1) cycle
                self%min_re = min(self%min_re, real(self%kd(i, j), dp))
            end do
        end do
        if (nq*ny == 1) self%min_re = 0.0_dp
        if (.not. (self%min_re > 0.0_dp) .and. nq*ny > 1) then
            call fatal_error(error, "veslide:kernel:build_kernel: the discrete kernel is not positive definite"// &
                " (min Re K_d <= 0); the collocation-alias variant loses definiteness for large"// &
                " Einf/E0 at speed: use the 'galerkin' or 'collocation' variant")
            return
        end if

    contains

        subroutine add_shells(m1, m2, acc)
            integer, intent(in) :: m1, m2
            complex(dp), intent(inout) :: acc(:, :)
            integer :: mm
            complex(dp) :: s
            if (m1 == 0) acc = (0.0_dp, 0.0_dp)
            !$omp parallel do schedule(dynamic) private(i, q, qr, nyq_x, nyq_y, nrep_x, nrep_y, rx, ry, s, mm)
            do j = 1, ny
                do i = 1, nq
                    if (i == 1 .and. j == 1) cycle
                    q = wavevector(i, j, nx, ny, lx_m, ly_m)
                    nyq_x = mod(nx, 2) == 0 .and. i == nx/2 + 1 .and. nx > 1
                    nyq_y = mod(ny, 2) == 0 .and. j == ny/2 + 1 .and. ny > 1
                    nrep_x = merge(2, 1, nyq_x); nrep_y = merge(2, 1, nyq_y)
                    s = (0.0_dp, 0.0_dp)
                    do ry = 1, nrep_y
                        do rx = 1, nrep_x
                            qr = q
                            if (rx == 2) qr(1) = -qr(1)
                            if (ry == 2) qr(2) = -qr(2)
                            do mm = m1, m2
                                s = s + shell_sum(mat, qr, velocity_m_s, a, b, variant, mm, use_x, use_y)
                            end do
                        end do
                    end do
                    acc(i, j) = acc(i, j) + s/real(nrep_x*nrep_y, dp)
                end do
            end do
            !$omp end parallel do
        end subroutine add_shells

    end subroutine build_kernel


end module veslide_kernel
