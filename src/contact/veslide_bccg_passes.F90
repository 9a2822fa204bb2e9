!> The fused passes of the bound-constrained CG (veslide_solver_bccg), on either backend: each a
!> dispatcher on the arrays' backend, its CPU twin here (`*_cpu`, the loops of the solver as they
!> were, OpenMP over rows) and its CUDA twin in veslide_bccg_passes.cu (same arguments, device
!> memory). Real fields are (nx, ny), spectra (na, nb) = the grid's spectral storage; row (or
!> spectral column) partial sums come back one per row, added in order by the solver. BCCG is
!> an active-set method for the hard wall, the one contact law it takes (veslide_solver_table):
!> its passes apply the hard wall's maps (contact, the pressure bound it clips at, the gap bound
!> it admits cells by; veslide_contact_law_maps.inc, and vs::hard_wall in the CUDA twins).
!>  statistics  g = x - gprev: per row [sum of g on the set, sum p g, sum p]; set size; min g
!>  residual    the set grows by the points outside it with g < 0; x = r = -g on it, 0 outside;
!>              per row [r.v_old, sum of r, sum of v_old, set size] over the (grown) set
!>  precondition  z^ = k^/(M N^2) (0 where M = 0); per spectral column sum wa |k|^2 w, times wb
!>  set_sum     per row sum of x over the set
!>  direction   v = x + beta v - shift on the set, 0 outside; x = v
!>  energy      per spectral column sum wa M |k|^2, times wb (v.Mv by Parseval)
!>  step        p = a p + alpha v on the set, clipped at 0 (the clipped amounts into x, the
!>              points leave the set); per row sum p (and the number clipped)
!>  update_transform / step_transform / gap_multiply: the spectral updates of p^ and of the gap
!>  add_points  p^ += the transforms of a few point values (clipped points): on the device the
!>              points' factors exp(-i q.x) are formed there too, into a work array the solve
!>              holds (no host arithmetic, no allocation per call)
!> The metric's multiplier M/N (`metric_t`) is an array on the host; on the device it is not
!> held: each pass that reads it forms it from K_d with the operations the array was filled with
!> (the same bits; 4 bytes per cell fewer).
module veslide_bccg_passes
    use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_int, c_double, c_long
    use, intrinsic :: iso_fortran_env, only: int8
    use veslide_kinds, only: dp, i8
    use veslide_grid, only: grid_t
    use veslide_arrays, only: rarray_t, carray_t, iarray_t, elements
    use veslide_device, only: device_download
    use veslide_threads, only: threaded
    implicit none
    private
    public :: metric_t, metric, metric_values, set_contact, statistics, residual, precondition, set_sum, direction, energy, step, &
              update_transform, step_transform, gap_multiply, add_points, clipped_points, max_points

    !> M/N = f |K_d| (`modulus`) or f Re K_d on the spectral storage, where a solve runs: on the
    !> host the array `ks`; on the device K_d (held by the caller while this is used), from which
    !> each pass forms it
    type :: metric_t
        integer :: n1 = 0, n2 = 0
        logical :: device = .false.
        type(rarray_t) :: ks                  !! host: the values
        type(c_ptr) :: kd = c_null_ptr        !! device: K_d
        real(dp) :: f = 0.0_dp
        logical :: modulus = .false.
    contains
        procedure :: destroy => metric_destroy
    end type metric_t

#ifdef VESLIDE_CUDA
    interface
        subroutine metric_gpu(n, ks, kd, f, modulus) bind(c, name='veslide_bccg_metric')
            import :: c_long, c_ptr, c_double, c_int
            integer(c_long), value :: n
            type(c_ptr), value :: ks, kd
            real(c_double), value :: f
            integer(c_int), value :: modulus
        end subroutine metric_gpu
        subroutine set_contact_gpu(n, act, p) bind(c, name='veslide_bccg_set_contact')
            import :: c_long, c_ptr
            integer(c_long), value :: n
            type(c_ptr), value :: act, p
        end subroutine set_contact_gpu
        !> rows(5, ny): [sum g on the set, sum p g, sum p, set size, min g]
        subroutine statistics_gpu(nx, ny, x, act, p, gprev, rows) bind(c, name='veslide_bccg_statistics')
            import :: c_int, c_ptr, c_double
            integer(c_int), value :: nx, ny
            type(c_ptr), value :: x, act, p
            real(c_double), value :: gprev
            real(c_double), intent(out) :: rows(*)
        end subroutine statistics_gpu
        !> rows(4, ny): [r.v_old, sum r, sum v_old, set size]
        subroutine residual_gpu(nx, ny, x, act, v, gbar, rows) bind(c, name='veslide_bccg_residual')
            import :: c_int, c_ptr, c_double
            integer(c_int), value :: nx, ny
            type(c_ptr), value :: x, act, v
            real(c_double), value :: gbar
            real(c_double), intent(out) :: rows(*)
        end subroutine residual_gpu
        !> cols(nb): sum of wa w |k|^2 per spectral column (times wb on the host)
        subroutine precondition_gpu(na, nb, k, kd, f, modulus, wa, n2, cols) bind(c, name='veslide_bccg_precondition')
            import :: c_int, c_ptr, c_double
            integer(c_int), value :: na, nb, modulus
            type(c_ptr), value :: k, kd, wa
            real(c_double), value :: f
            real(c_double), value :: n2
            real(c_double), intent(out) :: cols(*)
        end subroutine precondition_gpu
        subroutine set_sum_gpu(nx, ny, x, act, rows) bind(c, name='veslide_bccg_set_sum')
            import :: c_int, c_ptr, c_double
            integer(c_int), value :: nx, ny
            type(c_ptr), value :: x, act
            real(c_double), intent(out) :: rows(*)
        end subroutine set_sum_gpu
        subroutine direction_gpu(n, x, act, v, beta, shift) bind(c, name='veslide_bccg_direction')
            import :: c_long, c_ptr, c_double
            integer(c_long), value :: n
            type(c_ptr), value :: x, act, v
            real(c_double), value :: beta, shift
        end subroutine direction_gpu
        subroutine energy_gpu(na, nb, k, kd, f, modulus, wa, cols) bind(c, name='veslide_bccg_energy')
            import :: c_int, c_ptr, c_double
            integer(c_int), value :: na, nb, modulus
            type(c_ptr), value :: k, kd, wa
            real(c_double), value :: f
            real(c_double), intent(out) :: cols(*)
        end subroutine energy_gpu
        !> rows(2, ny): [sum p, points clipped]
        subroutine step_gpu(nx, ny, x, act, p, v, a, alpha, rows) bind(c, name='veslide_bccg_step')
            import :: c_int, c_ptr, c_double
            integer(c_int), value :: nx, ny
            type(c_ptr), value :: x, act, p, v
            real(c_double), value :: a, alpha
            real(c_double), intent(out) :: rows(*)
        end subroutine step_gpu
        !> mode 0: pk = a pk + alpha k;  1: that, then k = pk (b ks) - hk;  2: k = pk (a ks) - hk
        subroutine spectral_gpu(n, pk, k, kd, f, modulus, hk, a, alpha, b, mode) bind(c, name='veslide_bccg_spectral')
            import :: c_long, c_ptr, c_double, c_int
            integer(c_long), value :: n
            type(c_ptr), value :: pk, k, kd, hk
            real(c_double), value :: f, a, alpha, b
            integer(c_int), value :: modulus, mode
        end subroutine spectral_gpu
        !> pts(3, m): (i, j, value) of each point (i, j from 1); exy: (na + nb) x max_points
        subroutine point_transforms_gpu(na, nb, nx, m, pts, pk, exy) bind(c, name='veslide_bccg_point_transforms')
            import :: c_int, c_ptr, c_double
            integer(c_int), value :: na, nb, nx, m
            real(c_double), intent(in) :: pts(*)
            type(c_ptr), value :: pk, exy
        end subroutine point_transforms_gpu
    end interface
#endif

    integer(c_int), parameter :: PK_UPDATE = 0, PK_STEP = 1, PK_GAP = 2
    !> the most points add_points takes (its work array's columns on the device)
    integer, parameter :: max_points = 8

contains


    ! ---- dispatchers --------------------------------------------------------------------

    !> m = f |K_d| (`modulus`) or f Re K_d, where kd is: on the host its values, on the device
    !> K_d itself (which the caller keeps while m is used)
    subroutine metric(m, kd, f, modulus)
        type(metric_t), intent(inout) :: m
        type(carray_t), intent(in) :: kd
        real(dp), intent(in) :: f
        logical, intent(in) :: modulus
        call m%destroy()
        m%n1 = kd%n1; m%n2 = kd%n2; m%device = kd%device; m%f = f; m%modulus = modulus
        if (kd%device) then
            m%kd = kd%d; return
        end if
        call m%ks%create(kd%n1, kd%n2, .false.)
        call metric_cpu(m%ks%h, kd%h, f, modulus)
    end subroutine metric

    subroutine metric_destroy(self)
        class(metric_t), intent(inout) :: self
        call self%ks%destroy()
        self%kd = c_null_ptr; self%n1 = 0; self%n2 = 0; self%device = .false.
    end subroutine metric_destroy

    !> The values of m into ks (of m's shape, where m is: on the device formed as the passes form them)
    subroutine metric_values(m, ks)
        type(metric_t), intent(in) :: m
        type(rarray_t), intent(inout) :: ks
#ifdef VESLIDE_CUDA
        if (m%device) then
            call metric_gpu(elements(ks), ks%d, m%kd, m%f, modulus_flag(m)); return
        end if
#endif
        ks%h = m%ks%h
    end subroutine metric_values

    pure integer(c_int) function modulus_flag(m)
        type(metric_t), intent(in) :: m
        modulus_flag = merge(1_c_int, 0_c_int, m%modulus)
    end function modulus_flag

    !> act = 1 where p is in contact (the hard wall: p > 0), else 0
    subroutine set_contact(act, p)
        type(iarray_t), intent(inout) :: act
        type(rarray_t), intent(in) :: p
#ifdef VESLIDE_CUDA
        if (act%device) then
            call set_contact_gpu(elements(act), act%d, p%d); return
        end if
#endif
        act%h = merge(1_int8, 0_int8, hard_wall_in_contact(p%h))
    end subroutine set_contact

    subroutine statistics(x, act, p, gprev, rows, nact, gmin)
        type(rarray_t), intent(in) :: x, p
        type(iarray_t), intent(in) :: act
        real(dp), intent(in) :: gprev
        real(dp), intent(out) :: rows(:, :)
        integer(i8), intent(out) :: nact
        real(dp), intent(out) :: gmin
#ifdef VESLIDE_CUDA
        real(dp), allocatable :: out(:, :)
        if (x%device) then
            allocate (out(5, x%n2))
            call statistics_gpu(x%n1, x%n2, x%d, act%d, p%d, gprev, out)
            rows = out(1:3, :); nact = nint(sum(out(4, :)), i8); gmin = minval(out(5, :))
            return
        end if
#endif
        call statistics_cpu(x%h, act%h, p%h, gprev, rows, nact, gmin)
    end subroutine statistics

    !> rows(4, ny): per row [r.v_old, sum of r, sum of v_old, set size] over the grown set
    subroutine residual(x, act, v, gbar, rows)
        type(rarray_t), intent(inout) :: x
        type(iarray_t), intent(inout) :: act
        type(rarray_t), intent(in) :: v
        real(dp), intent(in) :: gbar
        real(dp), intent(out) :: rows(:, :)
#ifdef VESLIDE_CUDA
        if (x%device) then
            call residual_gpu(x%n1, x%n2, x%d, act%d, v%d, gbar, rows); return
        end if
#endif
        call residual_cpu(x%h, act%h, v%h, gbar, rows)
    end subroutine residual

    !> rows(ny): per row sum of x over the set
    subroutine set_sum(x, act, rows)
        type(rarray_t), intent(in) :: x
        type(iarray_t), intent(in) :: act
        real(dp), intent(out) :: rows(:)
#ifdef VESLIDE_CUDA
        if (x%device) then
            call set_sum_gpu(x%n1, x%n2, x%d, act%d, rows); return
        end if
#endif
        call set_sum_cpu(x%h, act%h, rows)
    end subroutine set_sum

    subroutine precondition(k, ks, wa, wa_dev, wb, n2, cols)
        type(carray_t), intent(inout) :: k
        type(metric_t), intent(in) :: ks
        type(rarray_t), intent(in) :: wa_dev
        real(dp), intent(in) :: wa(:), wb(:), n2
        real(dp), intent(out) :: cols(:)
#ifdef VESLIDE_CUDA
        if (k%device) then
            call precondition_gpu(k%n1, k%n2, k%d, ks%kd, ks%f, modulus_flag(ks), wa_dev%d, n2, cols)
            cols = wb*cols
            return
        end if
#endif
        call precondition_cpu(k%h, ks%ks%h, wa, wb, n2, cols)
    end subroutine precondition

    subroutine direction(x, act, v, beta, shift)
        type(rarray_t), intent(inout) :: x, v
        type(iarray_t), intent(in) :: act
        real(dp), intent(in) :: beta, shift
#ifdef VESLIDE_CUDA
        if (x%device) then
            call direction_gpu(elements(x), x%d, act%d, v%d, beta, shift); return
        end if
#endif
        call direction_cpu(x%h, act%h, v%h, beta, shift)
    end subroutine direction

    subroutine energy(k, ks, wa, wa_dev, wb, cols)
        type(carray_t), intent(in) :: k
        type(metric_t), intent(in) :: ks
        type(rarray_t), intent(in) :: wa_dev
        real(dp), intent(in) :: wa(:), wb(:)
        real(dp), intent(out) :: cols(:)
#ifdef VESLIDE_CUDA
        if (k%device) then
            call energy_gpu(k%n1, k%n2, k%d, ks%kd, ks%f, modulus_flag(ks), wa_dev%d, cols)
            cols = wb*cols
            return
        end if
#endif
        call energy_cpu(k%h, ks%ks%h, wa, wb, cols)
    end subroutine energy

    !> The step; `clip_rows` (device only): the points clipped per row, for clipped_points
    subroutine step(x, act, p, v, a, alpha, rows, nclip, clip_rows)
        type(rarray_t), intent(inout) :: x, p, v
        type(iarray_t), intent(inout) :: act
        real(dp), intent(in) :: a, alpha
        real(dp), intent(out) :: rows(:)
        integer, intent(out) :: nclip
        real(dp), intent(out) :: clip_rows(:)
#ifdef VESLIDE_CUDA
        real(dp), allocatable :: out(:, :)
        if (x%device) then
            allocate (out(2, x%n2))
            call step_gpu(x%n1, x%n2, x%d, act%d, p%d, v%d, a, alpha, out)
            rows = out(1, :); clip_rows = out(2, :); nclip = nint(sum(out(2, :)))
            return
        end if
#endif
        clip_rows = 0.0_dp
        call step_cpu(x%h, act%h, p%h, v%h, a, alpha, rows, nclip)
    end subroutine step

    !> pk = a pk + alpha k
    subroutine update_transform(pk, k, a, alpha)
        type(carray_t), intent(inout) :: pk
        type(carray_t), intent(in) :: k
        real(dp), intent(in) :: a, alpha
#ifdef VESLIDE_CUDA
        if (pk%device) then
            call spectral_gpu(elements(pk), pk%d, k%d, k%d, 0.0_dp, 0_c_int, k%d, a, alpha, 0.0_dp, PK_UPDATE); return
        end if
#endif
        call update_transform_cpu(pk%h, k%h, a, alpha)
    end subroutine update_transform

    !> pk = a pk + alpha k, then k = pk (a_new ks) - hk (the gap's transform)
    subroutine step_transform(pk, k, ks, hk, a, alpha, a_new)
        type(carray_t), intent(inout) :: pk, k
        type(metric_t), intent(in) :: ks
        type(carray_t), intent(in) :: hk
        real(dp), intent(in) :: a, alpha, a_new
#ifdef VESLIDE_CUDA
        if (pk%device) then
            call spectral_gpu(elements(pk), pk%d, k%d, ks%kd, ks%f, modulus_flag(ks), hk%d, a, alpha, a_new, PK_STEP)
            return
        end if
#endif
        call step_transform_cpu(pk%h, k%h, ks%ks%h, hk%h, a, alpha, a_new)
    end subroutine step_transform

    !> k = pk (a ks) - hk
    subroutine gap_multiply(k, pk, ks, hk, a)
        type(carray_t), intent(inout) :: k
        type(carray_t), intent(in) :: pk, hk
        type(metric_t), intent(in) :: ks
        real(dp), intent(in) :: a
#ifdef VESLIDE_CUDA
        if (k%device) then
            call spectral_gpu(elements(k), pk%d, k%d, ks%kd, ks%f, modulus_flag(ks), hk%d, a, 0.0_dp, 0.0_dp, PK_GAP)
            return
        end if
#endif
        call gap_multiply_cpu(k%h, pk%h, ks%ks%h, hk%h, a)
    end subroutine gap_multiply

    !> pk += the transform of the point values pts(3, k) at the cells (pts(1, k), pts(2, k)) of the
    !> whole grid (at most max_points): sum_k c_k exp(-i q.x_k), as the factors ex(i, k) ey(j, k)
    !> over the half-spectrum entries (i, j) of each storage position of `grid`. `work` holds the
    !> factors on the device ((na + nb) x max_points; unused on the host)
    subroutine add_points(pk, pts, grid, work)
        type(carray_t), intent(inout) :: pk
        real(dp), intent(in) :: pts(:, :)
        type(grid_t), intent(in) :: grid
        type(carray_t), intent(inout) :: work
        real(dp), parameter :: two_pi = 6.283185307179586476925286766559_dp
        complex(dp), allocatable :: ex(:, :), ey(:, :)
        integer :: i, j, k, m, ic, jc, nyg, nx, nq
#ifdef VESLIDE_CUDA
        if (pk%device) then
            ! (a grid on the device is not distributed: storage (a, b) is entry (a, b))
            call point_transforms_gpu(pk%n1, pk%n2, grid%nx, size(pts, 2), pts, pk%d, work%d); return
        end if
#endif
        m = size(pts, 2); nyg = grid%ny; nx = grid%nx; nq = nx/2 + 1
        allocate (ex(nq, m), ey(nyg, m))
        do k = 1, m
            ic = nint(pts(1, k)); jc = nint(pts(2, k))
            do i = 1, nq
                ex(i, k) = pts(3, k)*exp(cmplx(0.0_dp, -two_pi*real(modulo((i - 1)*(ic - 1), nx), dp)/nx, dp))
            end do
            do j = 1, nyg
                ey(j, k) = exp(cmplx(0.0_dp, -two_pi*real(modulo((j - 1)*(jc - 1), nyg), dp)/nyg, dp))
            end do
        end do
        call add_points_cpu(pk%h, ex, ey, grid)
    end subroutine add_points

    !> pts(:, k) = (i, j0 + j, value) of the first (at most max_n) non-zero entries of x, in the
    !> order of the process's rows; on the device `clip_rows` (the step's count per row) says
    !> which rows to read back
    subroutine clipped_points(x, clip_rows, j0, max_n, pts, k)
        type(rarray_t), intent(in) :: x
        real(dp), intent(in) :: clip_rows(:)
        integer, intent(in) :: j0, max_n
        real(dp), intent(out) :: pts(:, :)
        integer, intent(out) :: k
        integer :: i, j
        real(dp), allocatable :: row(:)
        k = 0
        if (x%device) then
            allocate (row(x%n1))
            do j = 1, x%n2
                if (k >= max_n) exit
                if (clip_rows(j) == 0.0_dp) cycle
                call device_download(row, row_address(x, j), 8_i8*x%n1)
                do i = 1, x%n1
                    if (row(i) /= 0.0_dp .and. k < max_n) then
                        k = k + 1
                        pts(:, k) = [real(i, dp), real(j0 + j, dp), row(i)]
                    end if
                end do
            end do
            return
        end if
        do j = 1, x%n2
            do i = 1, x%n1
                if (x%h(i, j) /= 0.0_dp .and. k < max_n) then
                    k = k + 1
                    pts(:, k) = [real(i, dp), real(j0 + j, dp), x%h(i, j)]
                end if
            end do
        end do
    end subroutine clipped_points

    !> The device address of row j of x
    function row_address(x, j) result(p)
        use, intrinsic :: iso_c_binding, only: c_intptr_t
        type(rarray_t), intent(in) :: x
        integer, intent(in) :: j
        type(c_ptr) :: p
        integer(c_intptr_t) :: a
        a = transfer(x%d, a) + int(j - 1, c_intptr_t)*int(x%n1, c_intptr_t)*8
        p = transfer(a, p)
    end function row_address

    ! ---- CPU twins ----------------------------------------------------------------------

    subroutine metric_cpu(ks, kd, f, modulus)
        real(dp), intent(out) :: ks(:, :)
        complex(dp), intent(in) :: kd(:, :)
        real(dp), intent(in) :: f
        logical, intent(in) :: modulus
        if (modulus) then
            ks = f*abs(kd)
        else
            ks = real(kd*f)
        end if
    end subroutine metric_cpu

    subroutine statistics_cpu(x, act, p, gprev, rows, nact, gmin)
        real(dp), intent(in) :: x(:, :), p(:, :)
        integer(int8), intent(in) :: act(:, :)
        real(dp), intent(in) :: gprev
        real(dp), intent(out) :: rows(:, :)
        integer(i8), intent(out) :: nact
        real(dp), intent(out) :: gmin
        real(dp) :: g, r3(3)
        integer :: i, j
        nact = 0; gmin = huge(1.0_dp)
        !$omp parallel do schedule(guided) if (threaded(size(x), size(x, 2))) &
        !$omp& private(i, g, r3) reduction(+:nact) reduction(min:gmin)
        do j = 1, size(x, 2)
            r3 = 0.0_dp
            do i = 1, size(x, 1)
                g = x(i, j) - gprev
                if (act(i, j) /= 0) then
                    nact = nact + 1; r3(1) = r3(1) + g
                end if
                gmin = min(gmin, g)
                r3(2) = r3(2) + p(i, j)*g
                r3(3) = r3(3) + p(i, j)
            end do
            rows(:, j) = r3
        end do
        !$omp end parallel do
    end subroutine statistics_cpu

    subroutine residual_cpu(x, act, v, gbar, rows)
        real(dp), intent(inout) :: x(:, :)
        integer(int8), intent(inout) :: act(:, :)
        real(dp), intent(in) :: v(:, :)
        real(dp), intent(in) :: gbar
        real(dp), intent(out) :: rows(:, :)
        real(dp) :: g, w(4)
        integer :: i, j
        !$omp parallel do schedule(guided) if (threaded(size(x), size(x, 2))) private(i, g, w)
        do j = 1, size(x, 2)
            w = 0.0_dp
            do i = 1, size(x, 1)
                g = x(i, j) - gbar
                if (act(i, j) == 0 .and. hard_wall_penetrates(g)) act(i, j) = 1_int8
                if (act(i, j) /= 0) then
                    x(i, j) = -g
                    w(1) = w(1) - g*v(i, j)
                    w(2) = w(2) - g
                    w(3) = w(3) + v(i, j)
                    w(4) = w(4) + 1.0_dp
                else
                    x(i, j) = 0.0_dp
                end if
            end do
            rows(:, j) = w
        end do
        !$omp end parallel do
    end subroutine residual_cpu

    subroutine set_sum_cpu(x, act, rows)
        real(dp), intent(in) :: x(:, :)
        integer(int8), intent(in) :: act(:, :)
        real(dp), intent(out) :: rows(:)
        real(dp) :: w
        integer :: i, j
        !$omp parallel do schedule(guided) if (threaded(size(x), size(x, 2))) private(i, w)
        do j = 1, size(x, 2)
            w = 0.0_dp
            do i = 1, size(x, 1)
                if (act(i, j) /= 0) w = w + x(i, j)
            end do
            rows(j) = w
        end do
        !$omp end parallel do
    end subroutine set_sum_cpu

    subroutine precondition_cpu(k, ks, wa, wb, n2, cols)
        complex(dp), intent(inout) :: k(:, :)
        real(dp), intent(in) :: ks(:, :), wa(:), wb(:), n2
        real(dp), intent(out) :: cols(:)
        real(dp) :: w, z
        integer :: i, j
        !$omp parallel do schedule(guided) if (threaded(2*size(k), size(k, 2))) private(i, w, z)
        do j = 1, size(k, 2)
            z = 0.0_dp
            do i = 1, size(k, 1)
                w = 0.0_dp
                if (ks(i, j) > 0.0_dp) w = 1.0_dp/(ks(i, j)*n2)
                z = z + wa(i)*w*(real(k(i, j))**2 + aimag(k(i, j))**2)
                k(i, j) = k(i, j)*w
            end do
            cols(j) = wb(j)*z
        end do
        !$omp end parallel do
    end subroutine precondition_cpu

    subroutine direction_cpu(x, act, v, beta, shift)
        real(dp), intent(inout) :: x(:, :), v(:, :)
        integer(int8), intent(in) :: act(:, :)
        real(dp), intent(in) :: beta, shift
        real(dp) :: z
        integer :: i, j
        !$omp parallel do schedule(guided) if (threaded(size(x), size(x, 2))) private(i, z)
        do j = 1, size(x, 2)
            do i = 1, size(x, 1)
                if (act(i, j) /= 0) then
                    z = x(i, j) + beta*v(i, j) - shift
                else
                    z = 0.0_dp
                end if
                v(i, j) = z
                x(i, j) = z
            end do
        end do
        !$omp end parallel do
    end subroutine direction_cpu

    subroutine energy_cpu(k, ks, wa, wb, cols)
        complex(dp), intent(in) :: k(:, :)
        real(dp), intent(in) :: ks(:, :), wa(:), wb(:)
        real(dp), intent(out) :: cols(:)
        real(dp) :: z
        integer :: i, j
        !$omp parallel do schedule(guided) if (threaded(2*size(k), size(k, 2))) private(i, z)
        do j = 1, size(k, 2)
            z = 0.0_dp
            do i = 1, size(k, 1)
                z = z + wa(i)*ks(i, j)*(real(k(i, j))**2 + aimag(k(i, j))**2)
            end do
            cols(j) = wb(j)*z
        end do
        !$omp end parallel do
    end subroutine energy_cpu

    subroutine step_cpu(x, act, p, v, a, alpha, rows, nclip)
        real(dp), intent(inout) :: x(:, :), p(:, :), v(:, :)
        integer(int8), intent(inout) :: act(:, :)
        real(dp), intent(in) :: a, alpha
        real(dp), intent(out) :: rows(:)
        integer, intent(out) :: nclip
        real(dp) :: pt, w
        integer :: i, j
        nclip = 0
        !$omp parallel do schedule(guided) if (threaded(size(x), size(x, 2))) private(i, pt, w) reduction(+:nclip)
        do j = 1, size(x, 2)
            w = 0.0_dp
            do i = 1, size(x, 1)
                x(i, j) = 0.0_dp
                if (act(i, j) /= 0) then
                    pt = a*p(i, j) + alpha*v(i, j)
                    if (hard_wall_below(pt)) then
                        x(i, j) = -pt
                        nclip = nclip + 1
                        pt = hard_wall_project(pt)
                        act(i, j) = 0_int8
                        v(i, j) = 0.0_dp
                    end if
                else
                    pt = 0.0_dp
                end if
                p(i, j) = pt
                w = w + pt
            end do
            rows(j) = w
        end do
        !$omp end parallel do
    end subroutine step_cpu

    subroutine update_transform_cpu(pk, k, a, alpha)
        complex(dp), intent(inout) :: pk(:, :)
        complex(dp), intent(in) :: k(:, :)
        real(dp), intent(in) :: a, alpha
        pk = a*pk + alpha*k
    end subroutine update_transform_cpu

    subroutine step_transform_cpu(pk, k, ks, hk, a, alpha, a_new)
        complex(dp), intent(inout) :: pk(:, :), k(:, :)
        real(dp), intent(in) :: ks(:, :)
        complex(dp), intent(in) :: hk(:, :)
        real(dp), intent(in) :: a, alpha, a_new
        integer :: i, j
        !$omp parallel do schedule(guided) if (threaded(2*size(pk), size(pk, 2))) private(i)
        do j = 1, size(pk, 2)
            do i = 1, size(pk, 1)
                pk(i, j) = a*pk(i, j) + alpha*k(i, j)
                k(i, j) = pk(i, j)*(a_new*ks(i, j)) - hk(i, j)
            end do
        end do
        !$omp end parallel do
    end subroutine step_transform_cpu

    subroutine gap_multiply_cpu(k, pk, ks, hk, a)
        complex(dp), intent(out) :: k(:, :)
        complex(dp), intent(in) :: pk(:, :), hk(:, :)
        real(dp), intent(in) :: ks(:, :), a
        integer :: i, j
        !$omp parallel do schedule(guided) if (threaded(2*size(k), size(k, 2))) private(i)
        do j = 1, size(k, 2)
            do i = 1, size(k, 1)
                k(i, j) = pk(i, j)*(a*ks(i, j)) - hk(i, j)
            end do
        end do
        !$omp end parallel do
    end subroutine gap_multiply_cpu

    subroutine add_points_cpu(pk, ex, ey, grid)
        complex(dp), intent(inout) :: pk(:, :)
        complex(dp), intent(in) :: ex(:, :), ey(:, :)
        type(grid_t), intent(in) :: grid
        complex(dp) :: s
        integer :: a, b, k, ij(2)
        !$omp parallel do schedule(guided) if (threaded(2*size(pk), size(pk, 2))) private(a, k, s, ij)
        do b = 1, size(pk, 2)
            do a = 1, size(pk, 1)
                ij = grid%spectral_index(a, b)
                s = (0.0_dp, 0.0_dp)
                do k = 1, size(ex, 2)
                    s = s + ex(ij(1), k)*ey(ij(2), k)
                end do
                pk(a, b) = pk(a, b) + s
            end do
        end do
        !$omp end parallel do
    end subroutine add_points_cpu

    include 'veslide_contact_law_maps.inc'

end module veslide_bccg_passes
