!> The fused passes of the preconditioned splitting (veslide_solver_pdr), on either backend: each
!> a dispatcher on the arrays' backend, its CPU twin here (`*_cpu`: the loops and array
!> expressions of the solver as they were) and its CUDA twin in veslide_pdr_passes.cu. In the
!> units of the solve, M = ks N is the metric |K|, K/N = s K_d, gs = gamma s, N the cells.
!>  step_constant   cm = gamma h^/(M + gamma K)/N^2 (the resolvent's constant part)
!>  resolvent       from z^ in k: hk = z^, k = x^/N = M z^/((M + gamma K) N) + cm, then the
!>                  inner heights hk = M (2 x^ - z^)
!>  scaled_product  k = (s K_d) p^ (the transform of K y, from the inner solve's p^)
!>  residual_sums   per row the sum of K y - H over the contact set, and its size (pdr takes the
!>                  hard wall only, veslide_solver_table: its contact, veslide_contact_law_maps.inc)
!>  residual_gap    per row sum(y g), sum(y), g = K y - H + d; the smallest g
!>  relax           z = z + lambda (y - x)
!>  add_scaled      a = a + s b (the device's relaxation in two parts: z - lambda x before the
!>                  inner solve, + lambda y after it, so that x need not be kept across it)
!>  full_contact    k = h^/((N^2 s) K_d) (the pressure of full contact, less its mean)
!>  gap_to_z        k = gamma g^/(M N^2) (z = y + gamma M^-1 g)
!>  combine         a = b + c, a = 1 + b, or a = b - a
module veslide_pdr_passes
    use, intrinsic :: iso_c_binding, only: c_ptr, c_int, c_double, c_long
    use veslide_kinds, only: dp, i8
    use veslide_arrays, only: rarray_t, carray_t, elements
    use veslide_bccg_passes, only: metric_t
    use veslide_threads, only: threaded
    implicit none
    private
    public :: step_constant, resolvent, scaled_product, residual_sums, residual_gap, relax, add_scaled, &
              full_contact, &
              gap_to_z, sum_of, one_plus, difference_from

    integer(c_int), parameter :: COMBINE_SUM = 0, COMBINE_ONE_PLUS = 1, COMBINE_DIFFERENCE = 2

#ifdef VESLIDE_CUDA
    interface
        !> mode 0: step_constant, 1: resolvent, 2: scaled_product, 3: full_contact, 4: gap_to_z
        !> the metric M/N formed from (ks_kd, ks_f, ks_modulus) where read (veslide_bccg_passes)
        subroutine spectral_gpu(n, mode, k, hk, cm, ks_kd, ks_f, ks_modulus, kd, pk, gamma, gs, c) &
            bind(c, name='veslide_pdr_spectral')
            import :: c_long, c_int, c_ptr, c_double
            integer(c_long), value :: n
            integer(c_int), value :: mode, ks_modulus
            type(c_ptr), value :: k, hk, cm, ks_kd, kd, pk
            real(c_double), value :: ks_f, gamma, gs, c
        end subroutine spectral_gpu
        !> rows(2, ny): [sum of x - (h - h_mean)/hs over p > 0, count]
        subroutine residual_sums_gpu(nx, ny, x, h, h_mean, hs, p, rows) bind(c, name='veslide_pdr_residual_sums')
            import :: c_int, c_ptr, c_double
            integer(c_int), value :: nx, ny
            type(c_ptr), value :: x, h, p
            real(c_double), value :: h_mean, hs
            real(c_double), intent(out) :: rows(*)
        end subroutine residual_sums_gpu
        !> rows(3, ny): [sum p g, sum p, min g]
        subroutine residual_gap_gpu(nx, ny, x, h, h_mean, hs, d, p, rows) bind(c, name='veslide_pdr_residual_gap')
            import :: c_int, c_ptr, c_double
            integer(c_int), value :: nx, ny
            type(c_ptr), value :: x, h, p
            real(c_double), value :: h_mean, hs, d
            real(c_double), intent(out) :: rows(*)
        end subroutine residual_gap_gpu
        subroutine relax_gpu(n, z, y, x, lambda) bind(c, name='veslide_pdr_relax')
            import :: c_long, c_ptr, c_double
            integer(c_long), value :: n
            type(c_ptr), value :: z, y, x
            real(c_double), value :: lambda
        end subroutine relax_gpu
        subroutine add_scaled_gpu(n, a, b, s) bind(c, name='veslide_pdr_add_scaled')
            import :: c_long, c_ptr, c_double
            integer(c_long), value :: n
            type(c_ptr), value :: a, b
            real(c_double), value :: s
        end subroutine add_scaled_gpu
        subroutine combine_gpu(n, a, b, c, mode) bind(c, name='veslide_pdr_combine')
            import :: c_long, c_ptr, c_int
            integer(c_long), value :: n
            type(c_ptr), value :: a, b, c
            integer(c_int), value :: mode
        end subroutine combine_gpu
    end interface
#endif

contains



    ! ---- dispatchers --------------------------------------------------------------------

    !> cm = gamma k/(ks + gs kd)/(n n) where ks > 0, else 0 (k holds h^)
    subroutine step_constant(cm, k, ks, kd, gamma, gs, n)
        type(carray_t), intent(inout) :: cm
        type(carray_t), intent(in) :: k, kd
        type(metric_t), intent(in) :: ks
        real(dp), intent(in) :: gamma, gs, n
#ifdef VESLIDE_CUDA
        if (cm%device) then
            call spectral_gpu(elements(cm), 0_c_int, k%d, k%d, cm%d, ks%kd, ks%f, flag(ks), kd%d, kd%d, gamma, gs, n)
            return
        end if
#endif
        call step_constant_cpu(cm%h, k%h, ks%ks%h, kd%h, gamma, gs, n)
    end subroutine step_constant

    !> The resolvent of z (z^ in k) and the inner heights: see the module's header
    subroutine resolvent(k, hk, ks, kd, cm, gs, n)
        type(carray_t), intent(inout) :: k, hk
        type(metric_t), intent(in) :: ks
        type(carray_t), intent(in) :: kd, cm
        real(dp), intent(in) :: gs, n
#ifdef VESLIDE_CUDA
        if (k%device) then
            call spectral_gpu(elements(k), 1_c_int, k%d, hk%d, cm%d, ks%kd, ks%f, flag(ks), kd%d, kd%d, 0.0_dp, gs, n)
            return
        end if
#endif
        call resolvent_cpu(k%h, hk%h, ks%ks%h, kd%h, cm%h, gs, n)
    end subroutine resolvent

    !> k = (s kd) pk
    subroutine scaled_product(k, kd, pk, s)
        type(carray_t), intent(inout) :: k
        type(carray_t), intent(in) :: kd, pk
        real(dp), intent(in) :: s
#ifdef VESLIDE_CUDA
        if (k%device) then
            call spectral_gpu(elements(k), 2_c_int, k%d, k%d, k%d, kd%d, 0.0_dp, 0_c_int, kd%d, pk%d, 0.0_dp, 0.0_dp, s)
            return
        end if
#endif
        call scaled_product_cpu(k%h, kd%h, pk%h, s)
    end subroutine scaled_product

    !> k = k/(c kd) where ks > 0, else 0
    subroutine full_contact(k, ks, kd, c)
        type(carray_t), intent(inout) :: k
        type(metric_t), intent(in) :: ks
        type(carray_t), intent(in) :: kd
        real(dp), intent(in) :: c
#ifdef VESLIDE_CUDA
        if (k%device) then
            call spectral_gpu(elements(k), 3_c_int, k%d, k%d, k%d, ks%kd, ks%f, flag(ks), kd%d, kd%d, 0.0_dp, 0.0_dp, c)
            return
        end if
#endif
        call full_contact_cpu(k%h, ks%ks%h, kd%h, c)
    end subroutine full_contact

    !> k = k (gamma/(ks n n)) where ks > 0, else 0
    subroutine gap_to_z(k, ks, gamma, n)
        type(carray_t), intent(inout) :: k
        type(metric_t), intent(in) :: ks
        real(dp), intent(in) :: gamma, n
#ifdef VESLIDE_CUDA
        if (k%device) then
            call spectral_gpu(elements(k), 4_c_int, k%d, k%d, k%d, ks%kd, ks%f, flag(ks), k%d, k%d, gamma, 0.0_dp, n)
            return
        end if
#endif
        call gap_to_z_cpu(k%h, ks%ks%h, gamma, n)
    end subroutine gap_to_z

    !> The metric's form on the device (1: f |K_d|, 0: f Re K_d)
    pure integer(c_int) function flag(ks)
        type(metric_t), intent(in) :: ks
        flag = merge(1_c_int, 0_c_int, ks%modulus)
    end function flag

    !> rows(j) = sum over the contact cells (p > 0) of row j of x - (h - h_mean)/hs; nc their number
    subroutine residual_sums(x, h, h_mean, hs, p, rows, nc)
        type(rarray_t), intent(in) :: x, h, p
        real(dp), intent(in) :: h_mean, hs
        real(dp), intent(out) :: rows(:)
        integer(i8), intent(out) :: nc
#ifdef VESLIDE_CUDA
        real(dp), allocatable :: out(:, :)
        if (x%device) then
            allocate (out(2, x%n2))
            call residual_sums_gpu(x%n1, x%n2, x%d, h%d, h_mean, hs, p%d, out)
            rows = out(1, :); nc = nint(sum(out(2, :)), i8)
            return
        end if
#endif
        call residual_sums_cpu(x%h, h%h, h_mean, hs, p%h, rows, nc)
    end subroutine residual_sums

    !> g = x - (h - h_mean)/hs + d: rows(:, j) = [sum p g, sum p] of row j; gmin the smallest g
    subroutine residual_gap(x, h, h_mean, hs, d, p, rows, gmin)
        type(rarray_t), intent(in) :: x, h, p
        real(dp), intent(in) :: h_mean, hs, d
        real(dp), intent(out) :: rows(:, :), gmin
#ifdef VESLIDE_CUDA
        real(dp), allocatable :: out(:, :)
        if (x%device) then
            allocate (out(3, x%n2))
            call residual_gap_gpu(x%n1, x%n2, x%d, h%d, h_mean, hs, d, p%d, out)
            rows = out(1:2, :); gmin = minval(out(3, :))
            return
        end if
#endif
        call residual_gap_cpu(x%h, h%h, h_mean, hs, d, p%h, rows, gmin)
    end subroutine residual_gap

    !> z = z + lambda (y - x)
    subroutine relax(z, y, x, lambda)
        type(rarray_t), intent(inout) :: z
        type(rarray_t), intent(in) :: y, x
        real(dp), intent(in) :: lambda
#ifdef VESLIDE_CUDA
        if (z%device) then
            call relax_gpu(elements(z), z%d, y%d, x%d, lambda); return
        end if
#endif
        call relax_cpu(z%h, y%h, x%h, lambda)
    end subroutine relax

    !> a = a + s b
    subroutine add_scaled(a, b, s)
        type(rarray_t), intent(inout) :: a
        type(rarray_t), intent(in) :: b
        real(dp), intent(in) :: s
#ifdef VESLIDE_CUDA
        if (a%device) then
            call add_scaled_gpu(elements(a), a%d, b%d, s); return
        end if
#endif
        call add_scaled_cpu(a%h, b%h, s)
    end subroutine add_scaled

    !> a = b + c
    subroutine sum_of(a, b, c)
        type(rarray_t), intent(inout) :: a
        type(rarray_t), intent(in) :: b, c
        call combine(a, b, c, COMBINE_SUM)
    end subroutine sum_of

    !> a = 1 + b
    subroutine one_plus(a, b)
        type(rarray_t), intent(inout) :: a
        type(rarray_t), intent(in) :: b
        call combine(a, b, b, COMBINE_ONE_PLUS)
    end subroutine one_plus

    !> a = b - a
    subroutine difference_from(a, b)
        type(rarray_t), intent(inout) :: a
        type(rarray_t), intent(in) :: b
        call combine(a, b, b, COMBINE_DIFFERENCE)
    end subroutine difference_from

    subroutine combine(a, b, c, mode)
        type(rarray_t), intent(inout) :: a
        type(rarray_t), intent(in) :: b, c
        integer(c_int), intent(in) :: mode
#ifdef VESLIDE_CUDA
        if (a%device) then
            call combine_gpu(elements(a), a%d, b%d, c%d, mode); return
        end if
#endif
        call combine_cpu(a%h, b%h, c%h, mode)
    end subroutine combine

    ! ---- CPU twins ----------------------------------------------------------------------

    subroutine step_constant_cpu(cm, k, ks, kd, gamma, gs, n)
        complex(dp), intent(out) :: cm(:, :)
        complex(dp), intent(in) :: k(:, :), kd(:, :)
        real(dp), intent(in) :: ks(:, :), gamma, gs, n
        integer :: i, j
        do j = 1, size(cm, 2)
            do i = 1, size(cm, 1)
                if (ks(i, j) > 0.0_dp) then
                    cm(i, j) = gamma*k(i, j)/(ks(i, j) + gs*kd(i, j))/(n*n)
                else
                    cm(i, j) = (0.0_dp, 0.0_dp)
                end if
            end do
        end do
    end subroutine step_constant_cpu

    subroutine resolvent_cpu(k, hk, ks, kd, cm, gs, n)
        complex(dp), intent(inout) :: k(:, :), hk(:, :)
        real(dp), intent(in) :: ks(:, :)
        complex(dp), intent(in) :: kd(:, :), cm(:, :)
        real(dp), intent(in) :: gs, n
        integer :: i, j
        !$omp parallel do schedule(guided) if (threaded(2*size(k), size(k, 2))) private(i)
        do j = 1, size(k, 2)
            do i = 1, size(k, 1)
                hk(i, j) = k(i, j)
                if (ks(i, j) > 0.0_dp) then
                    k(i, j) = ks(i, j)*k(i, j)/((ks(i, j) + gs*kd(i, j))*n) + cm(i, j)
                else
                    k(i, j) = k(i, j)/n
                end if
                hk(i, j) = ks(i, j)*(2.0_dp*n*k(i, j) - hk(i, j))
            end do
        end do
        !$omp end parallel do
    end subroutine resolvent_cpu

    subroutine scaled_product_cpu(k, kd, pk, s)
        complex(dp), intent(out) :: k(:, :)
        complex(dp), intent(in) :: kd(:, :), pk(:, :)
        real(dp), intent(in) :: s
        k = (s*kd)*pk
    end subroutine scaled_product_cpu

    subroutine full_contact_cpu(k, ks, kd, c)
        complex(dp), intent(inout) :: k(:, :)
        real(dp), intent(in) :: ks(:, :), c
        complex(dp), intent(in) :: kd(:, :)
        where (ks > 0.0_dp)
            k = k/(c*kd)
        elsewhere
            k = (0.0_dp, 0.0_dp)
        end where
    end subroutine full_contact_cpu

    subroutine gap_to_z_cpu(k, ks, gamma, n)
        complex(dp), intent(inout) :: k(:, :)
        real(dp), intent(in) :: ks(:, :), gamma, n
        where (ks > 0.0_dp)
            k = k*(gamma/(ks*n*n))
        elsewhere
            k = (0.0_dp, 0.0_dp)
        end where
    end subroutine gap_to_z_cpu

    subroutine residual_sums_cpu(x, h, h_mean, hs, p, rows, nc)
        real(dp), intent(in) :: x(:, :), h(:, :), p(:, :), h_mean, hs
        real(dp), intent(out) :: rows(:)
        integer(i8), intent(out) :: nc
        real(dp) :: g
        integer :: i, j
        nc = 0
        !$omp parallel do schedule(guided) if (threaded(size(x), size(x, 2))) private(i, g) reduction(+:nc)
        do j = 1, size(x, 2)
            g = 0.0_dp
            do i = 1, size(x, 1)
                if (hard_wall_in_contact(p(i, j))) then
                    nc = nc + 1; g = g + (x(i, j) - (h(i, j) - h_mean)/hs)
                end if
            end do
            rows(j) = g
        end do
        !$omp end parallel do
    end subroutine residual_sums_cpu

    subroutine residual_gap_cpu(x, h, h_mean, hs, d, p, rows, gmin)
        real(dp), intent(in) :: x(:, :), h(:, :), p(:, :), h_mean, hs, d
        real(dp), intent(out) :: rows(:, :), gmin
        real(dp) :: g, t2(2)
        integer :: i, j
        gmin = huge(1.0_dp)
        !$omp parallel do schedule(guided) if (threaded(size(x), size(x, 2))) private(i, g, t2) reduction(min:gmin)
        do j = 1, size(x, 2)
            t2 = 0.0_dp
            do i = 1, size(x, 1)
                g = x(i, j) - (h(i, j) - h_mean)/hs + d
                gmin = min(gmin, g)
                t2(1) = t2(1) + p(i, j)*g
                t2(2) = t2(2) + p(i, j)
            end do
            rows(:, j) = t2
        end do
        !$omp end parallel do
    end subroutine residual_gap_cpu

    subroutine relax_cpu(z, y, x, lambda)
        real(dp), intent(inout) :: z(:, :)
        real(dp), intent(in) :: y(:, :), x(:, :), lambda
        integer :: i, j
        !$omp parallel do schedule(guided) if (threaded(size(z), size(z, 2))) private(i)
        do j = 1, size(z, 2)
            do i = 1, size(z, 1)
                z(i, j) = z(i, j) + lambda*(y(i, j) - x(i, j))
            end do
        end do
        !$omp end parallel do
    end subroutine relax_cpu

    subroutine add_scaled_cpu(a, b, s)
        real(dp), intent(inout) :: a(:, :)
        real(dp), intent(in) :: b(:, :), s
        integer :: i, j
        !$omp parallel do schedule(guided) if (threaded(size(a), size(a, 2))) private(i)
        do j = 1, size(a, 2)
            do i = 1, size(a, 1)
                a(i, j) = a(i, j) + s*b(i, j)
            end do
        end do
        !$omp end parallel do
    end subroutine add_scaled_cpu

    subroutine combine_cpu(a, b, c, mode)
        real(dp), intent(inout) :: a(:, :)
        real(dp), intent(in) :: b(:, :), c(:, :)
        integer(c_int), intent(in) :: mode
        integer :: j
        !$omp parallel do schedule(static) if (threaded(size(a), size(a, 2)))
        do j = 1, size(a, 2)
            select case (mode)
            case (COMBINE_SUM); a(:, j) = b(:, j) + c(:, j)
            case (COMBINE_ONE_PLUS); a(:, j) = 1.0_dp + b(:, j)
            case default; a(:, j) = b(:, j) - a(:, j)
            end select
        end do
        !$omp end parallel do
    end subroutine combine_cpu

    include 'veslide_contact_law_maps.inc'

end module veslide_pdr_passes
