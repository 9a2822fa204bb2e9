!> The passes of the conjugate gradients on the gap (veslide_solver_gcg), on either backend: each
!> a dispatcher on the arrays' backend, its CPU twin here (`*_cpu`: OpenMP over rows, the
!> arithmetic of the array expressions they replaced, so that the host's results are those of
!> before, bit for bit) and its CUDA twin in veslide_gcg_passes.cu (the same arguments on device
!> memory). The passes that apply the adhesive law take its kind and its parameters in the
!> solve's units (sigma0 and rho) and choose the law's maps once per call (one CPU loop per law;
!> the CUDA functors take the law as a template argument). Sums come back per row (rows(k, j)),
!> added in order by the caller (veslide_collective); extremes come back as this process's. The
!> free set and Dugdale's edge are int8 sets (1 in, 0 out).
!>  attract     at = r + sigma(g); edge = (g == rho) for Dugdale's law, 0 for another; per row the sum of at and the
!>              count over the open cells off the edge, and the edge's count
!>  free_set    the free set from the multiplier lam (and the held edge cells' attraction); per
!>              row the sum of at and the count over it
!>  centre      at = at - lam on the free set, 0 off it; the gradient's largest violation
!>  spectral    a Fourier multiplier of the solve on the half-spectrum (SPECTRAL_*)
!>  mask        a = 0 off the free set; per row its sum and the set's count
!>  dot         per row the sum of a b;  shift_dot: a = a - c on the free set first
!>  direction   t = z + beta t on the free set, 0 off it; per row the sum of at t
!>  curvature   per row the free set's sums of pz t, pz, 1 and t
!>  step        g = max(g - tau t, 0) (Dugdale: stopped at the zone's edge, in `edge`); per row
!>              the cells stopped; the least g before the clip
!>  gap_sums    (g clipped at 0 first, optionally) per row the sum of g and the open cells' count
!>  shift_open  g = g + c on the open cells; the least g
!>  combine     the element-wise combinations of the solve (COMBINE_*)
!>  extremes    the least and the largest entry
module veslide_gcg_passes
    use, intrinsic :: iso_c_binding, only: c_ptr, c_int, c_double, c_long, c_null_ptr
    use, intrinsic :: iso_fortran_env, only: int8
    use veslide_kinds, only: dp
    use veslide_arrays, only: rarray_t, carray_t, iarray_t, elements
    use veslide_contact_law, only: LAW_EXPONENTIAL, LAW_DUGDALE
    use veslide_threads, only: threaded
    implicit none
    private
    public :: gcg_attract, gcg_free_set, gcg_centre, gcg_spectral, gcg_mask, gcg_dot, gcg_shift_dot, gcg_direction, &
              gcg_curvature, gcg_step, gcg_gap_sums, gcg_shift_open, gcg_combine, gcg_extremes
    public :: SPECTRAL_A, SPECTRAL_K, SPECTRAL_OPERATOR, SPECTRAL_RESOLVENT, SPECTRAL_START
    public :: COMBINE_SUM, COMBINE_DIFFERENCE, COMBINE_REFLECT, COMBINE_ACCUMULATE, COMBINE_PRESSURE, &
              COMBINE_DISPLACEMENT, COMBINE_FROM, COMBINE_AXPY

    !> gcg_spectral's multipliers of k (A the real `ainv`, K the complex `kinv`, N the cells):
    !>  A: k A;  K: k/((A N + c1) N) where A /= 0, else 0 (c1 the law's stiffness);
    !>  OPERATOR: k K;  RESOLVENT: k/((1 + K/A) N) where K /= 0, else k/N;  START: k (K/A)/N where
    !>  K /= 0, else 0 (A the splitting's metric over its step: gamma K/|K| where it is |K|/gamma)
    integer(c_int), parameter :: SPECTRAL_A = 0, SPECTRAL_K = 1, SPECTRAL_OPERATOR = 2, SPECTRAL_RESOLVENT = 3, &
                                 SPECTRAL_START = 4
    !> gcg_combine's element-wise combinations into d:
    !>  SUM: a + b;  DIFFERENCE: (a - b) - c1;  REFLECT: a - 2 b;  ACCUMULATE: d + c1 (a - b);
    !>  PRESSURE: c1 + c2 (a - c3);  DISPLACEMENT: c2 ((a + b) - c1);  FROM: c1 - a;
    !>  AXPY: d - c1 a
    integer(c_int), parameter :: COMBINE_SUM = 0, COMBINE_DIFFERENCE = 1, COMBINE_REFLECT = 2, COMBINE_ACCUMULATE = 3, &
                                 COMBINE_PRESSURE = 4, COMBINE_DISPLACEMENT = 5, COMBINE_FROM = 6, COMBINE_AXPY = 7

    !> veslide_gcg_rows's passes (their ids in veslide_gcg_passes.cu)
    integer(c_int), parameter :: ROWS_ATTRACT = 0, ROWS_FREE_SET = 1, ROWS_CENTRE = 2, ROWS_MASK = 3, ROWS_DOT = 4, &
                                 ROWS_SHIFT_DOT = 5, ROWS_DIRECTION = 6, ROWS_CURVATURE = 7, ROWS_STEP = 8, &
                                 ROWS_GAP_SUMS = 9, ROWS_SHIFT_OPEN = 10, ROWS_EXTREMES = 11

#ifdef VESLIDE_CUDA
    interface
        !> A pass with row values (`mode` a ROWS_* id): its K values per row in rows(K*ny)
        subroutine rows_gpu(mode, law, s0, rho, nx, ny, a, b, c, d, free, edge, x1, x2, rows) &
            bind(c, name='veslide_gcg_rows')
            import :: c_int, c_ptr, c_double
            integer(c_int), value :: mode, law, nx, ny
            real(c_double), value :: s0, rho, x1, x2
            type(c_ptr), value :: a, b, c, d, free, edge
            real(c_double), intent(out) :: rows(*)
        end subroutine rows_gpu
        subroutine spectral_gpu(n, mode, k, ainv, kinv, c1, cells) bind(c, name='veslide_gcg_spectral')
            import :: c_int, c_long, c_ptr, c_double
            integer(c_long), value :: n
            integer(c_int), value :: mode
            type(c_ptr), value :: k, ainv, kinv
            real(c_double), value :: c1, cells
        end subroutine spectral_gpu
        subroutine combine_gpu(n, mode, d, a, b, c1, c2, c3) bind(c, name='veslide_gcg_combine')
            import :: c_int, c_long, c_ptr, c_double
            integer(c_long), value :: n
            integer(c_int), value :: mode
            type(c_ptr), value :: d, a, b
            real(c_double), value :: c1, c2, c3
        end subroutine combine_gpu
    end interface
#endif

contains

    ! ---- dispatchers --------------------------------------------------------------------

    !> at = r + sigma(g) (the law `law`: LAW_EXPONENTIAL or LAW_DUGDALE, sigma0 `s0`, range `rho`);
    !> edge = (g == rho) for Dugdale's law, 0 for the exponential one. rows(:, j) = [sum of at, count] over the open cells of row j
    !> off the edge, and the edge's count
    subroutine gcg_attract(law, s0, rho, g, r, at, edge, rows)
        integer, intent(in) :: law
        real(dp), intent(in) :: s0, rho
        type(rarray_t), intent(in) :: g, r
        type(rarray_t), intent(inout) :: at
        type(iarray_t), intent(inout) :: edge
        real(dp), intent(out) :: rows(:, :)
#ifdef VESLIDE_CUDA
        if (g%device) then
            call device_rows(ROWS_ATTRACT, 3, law, s0, rho, g%d, r%d, at%d, c_null_ptr, c_null_ptr, edge%d, &
                             0.0_dp, 0.0_dp, rows, g%n1); return
        end if
#endif
        select case (law)
        case (LAW_EXPONENTIAL)
            call attract_exponential(s0, rho, g%h, r%h, at%h, edge%h, rows)
        case (LAW_DUGDALE)
            call attract_dugdale(s0, rho, g%h, r%h, at%h, edge%h, rows)
        case default
            error stop "veslide:gcg_passes:gcg_attract: a contact law this pass does not take"
        end select
    end subroutine gcg_attract

    !> free = (g > 0 and off the edge) or (g <= 0 and at - lam < 0); where `held` (Dugdale's
    !> edge holds cells), an edge cell is free where r - lam > 0 or r - lam < -s0 and its at the
    !> attraction of the law's graph there. rows(:, j) = [sum of at, count] over the free set
    subroutine gcg_free_set(g, r, at, free, edge, lam, s0, held, rows)
        type(rarray_t), intent(in) :: g, r
        type(rarray_t), intent(inout) :: at
        type(iarray_t), intent(inout) :: free
        type(iarray_t), intent(in) :: edge
        real(dp), intent(in) :: lam, s0
        logical, intent(in) :: held
        real(dp), intent(out) :: rows(:, :)
#ifdef VESLIDE_CUDA
        if (g%device) then
            call device_rows(ROWS_FREE_SET, 2, merge(1, 0, held), s0, 0.0_dp, g%d, r%d, at%d, c_null_ptr, free%d, edge%d, &
                             lam, 0.0_dp, rows, g%n1); return
        end if
#endif
        call free_set_cpu(g%h, r%h, at%h, free%h, edge%h, lam, s0, held, rows)
    end subroutine gcg_free_set

    !> at = at - lam on the free set, 0 off it; err = the largest violation of this process's
    !> cells: |at - lam| where open, max(lam - at, 0) where closed (0 for an edge cell off the set)
    subroutine gcg_centre(g, at, free, edge, lam, err)
        type(rarray_t), intent(in) :: g
        type(rarray_t), intent(inout) :: at
        type(iarray_t), intent(in) :: free, edge
        real(dp), intent(in) :: lam
        real(dp), intent(out) :: err
#ifdef VESLIDE_CUDA
        real(dp) :: rows(1, g%n2)
        if (g%device) then
            call device_rows(ROWS_CENTRE, 1, 0, 0.0_dp, 0.0_dp, g%d, c_null_ptr, at%d, c_null_ptr, free%d, edge%d, &
                             lam, 0.0_dp, rows, g%n1)
            err = -minval(rows); return
        end if
#endif
        call centre_cpu(g%h, at%h, free%h, edge%h, lam, err)
    end subroutine gcg_centre

    !> k = k times the multiplier `mode` (SPECTRAL_*) of `ainv` (real) or `kinv` (complex), on
    !> the half-spectrum; `c1` the law's stiffness (K) or gamma (RESOLVENT, START), `cells` N
    subroutine gcg_spectral(mode, k, ainv, kinv, c1, cells)
        integer(c_int), intent(in) :: mode
        type(carray_t), intent(inout) :: k
        type(rarray_t), intent(in) :: ainv
        type(carray_t), intent(in) :: kinv
        real(dp), intent(in) :: c1, cells
#ifdef VESLIDE_CUDA
        if (k%device) then
            call spectral_gpu(elements(k), mode, k%d, ainv%d, kinv%d, c1, cells); return
        end if
#endif
        select case (mode)
        case (SPECTRAL_A, SPECTRAL_K)
            call spectral_real_cpu(mode, k%h, ainv%h, c1, cells)
        case default
            call spectral_complex_cpu(mode, k%h, kinv%h, ainv%h, cells)
        end select
    end subroutine gcg_spectral

    !> a = 0 off the free set; rows(:, j) = [sum of a, count] over the free set
    subroutine gcg_mask(a, free, rows)
        type(rarray_t), intent(inout) :: a
        type(iarray_t), intent(in) :: free
        real(dp), intent(out) :: rows(:, :)
#ifdef VESLIDE_CUDA
        if (a%device) then
            call device_rows(ROWS_MASK, 2, 0, 0.0_dp, 0.0_dp, a%d, c_null_ptr, c_null_ptr, c_null_ptr, free%d, &
                             c_null_ptr, 0.0_dp, 0.0_dp, rows, a%n1); return
        end if
#endif
        call mask_cpu(a%h, free%h, rows)
    end subroutine gcg_mask

    !> rows(1, j) = the sum of a b over row j
    subroutine gcg_dot(a, b, rows)
        type(rarray_t), intent(in) :: a, b
        real(dp), intent(out) :: rows(:, :)
#ifdef VESLIDE_CUDA
        if (a%device) then
            call device_rows(ROWS_DOT, 1, 0, 0.0_dp, 0.0_dp, a%d, b%d, c_null_ptr, c_null_ptr, c_null_ptr, c_null_ptr, &
                             0.0_dp, 0.0_dp, rows, a%n1); return
        end if
#endif
        call dot_cpu(a%h, b%h, rows)
    end subroutine gcg_dot

    !> a = a - c on the free set; rows(1, j) = the sum of a b over row j
    subroutine gcg_shift_dot(a, b, free, c, rows)
        type(rarray_t), intent(inout) :: a
        type(rarray_t), intent(in) :: b
        type(iarray_t), intent(in) :: free
        real(dp), intent(in) :: c
        real(dp), intent(out) :: rows(:, :)
#ifdef VESLIDE_CUDA
        if (a%device) then
            call device_rows(ROWS_SHIFT_DOT, 1, 0, 0.0_dp, 0.0_dp, a%d, b%d, c_null_ptr, c_null_ptr, free%d, c_null_ptr, &
                             c, 0.0_dp, rows, a%n1); return
        end if
#endif
        call shift_dot_cpu(a%h, b%h, free%h, c, rows)
    end subroutine gcg_shift_dot

    !> t = z + beta t on the free set, 0 off it; rows(1, j) = the sum of at t over row j
    subroutine gcg_direction(z, at, t, free, beta, rows)
        type(rarray_t), intent(in) :: z, at
        type(rarray_t), intent(inout) :: t
        type(iarray_t), intent(in) :: free
        real(dp), intent(in) :: beta
        real(dp), intent(out) :: rows(:, :)
#ifdef VESLIDE_CUDA
        if (t%device) then
            call device_rows(ROWS_DIRECTION, 1, 0, 0.0_dp, 0.0_dp, z%d, at%d, t%d, c_null_ptr, free%d, c_null_ptr, &
                             beta, 0.0_dp, rows, t%n1); return
        end if
#endif
        call direction_cpu(z%h, at%h, t%h, free%h, beta, rows)
    end subroutine gcg_direction

    !> rows(:, j) = [sum of pz t, sum of pz, count, sum of t] over the free set of row j
    subroutine gcg_curvature(pz, t, free, rows)
        type(rarray_t), intent(in) :: pz, t
        type(iarray_t), intent(in) :: free
        real(dp), intent(out) :: rows(:, :)
#ifdef VESLIDE_CUDA
        if (t%device) then
            call device_rows(ROWS_CURVATURE, 4, 0, 0.0_dp, 0.0_dp, pz%d, t%d, c_null_ptr, c_null_ptr, free%d, c_null_ptr, &
                             0.0_dp, 0.0_dp, rows, t%n1); return
        end if
#endif
        call curvature_cpu(pz%h, t%h, free%h, rows)
    end subroutine gcg_curvature

    !> g = max(g - tau t, 0); Dugdale's law (`law`, range `rho`): a cell whose step crossed the
    !> zone's edge stops there (g = rho, edge = 1; edge = 0 elsewhere). rows(1, j) = the cells of
    !> row j stopped, rows(2, j) = the cells of row j clipped (g - tau t < 0); gmin = the least
    !> g - tau t (this process's)
    subroutine gcg_step(law, rho, g, t, tau, edge, rows, gmin)
        integer, intent(in) :: law
        real(dp), intent(in) :: rho, tau
        type(rarray_t), intent(inout) :: g
        type(rarray_t), intent(in) :: t
        type(iarray_t), intent(inout) :: edge
        real(dp), intent(out) :: rows(:, :), gmin
#ifdef VESLIDE_CUDA
        real(dp) :: out(3, g%n2)
        if (g%device) then
            call device_rows(ROWS_STEP, 3, law, 0.0_dp, rho, g%d, t%d, c_null_ptr, c_null_ptr, c_null_ptr, edge%d, &
                             tau, 0.0_dp, out, g%n1)
            rows(1:2, :) = out(1:2, :); gmin = minval(out(3, :)); return
        end if
#endif
        if (law == LAW_DUGDALE) then
            call step_dugdale(rho, g%h, t%h, tau, edge%h, rows, gmin)
        else
            call step_smooth(g%h, t%h, tau, rows, gmin)
        end if
    end subroutine gcg_step

    !> (g = max(g, 0) first where `clip`) rows(:, j) = [sum of g, count of g > 0] over row j
    subroutine gcg_gap_sums(g, clip, rows)
        type(rarray_t), intent(inout) :: g
        logical, intent(in) :: clip
        real(dp), intent(out) :: rows(:, :)
#ifdef VESLIDE_CUDA
        if (g%device) then
            call device_rows(ROWS_GAP_SUMS, 2, merge(1, 0, clip), 0.0_dp, 0.0_dp, g%d, c_null_ptr, c_null_ptr, c_null_ptr, &
                             c_null_ptr, c_null_ptr, 0.0_dp, 0.0_dp, rows, g%n1); return
        end if
#endif
        call gap_sums_cpu(g%h, clip, rows)
    end subroutine gcg_gap_sums

    !> g = g + c where g > 0; gmin = the least g after (this process's)
    subroutine gcg_shift_open(g, c, gmin)
        type(rarray_t), intent(inout) :: g
        real(dp), intent(in) :: c
        real(dp), intent(out) :: gmin
#ifdef VESLIDE_CUDA
        real(dp) :: rows(1, g%n2)
        if (g%device) then
            call device_rows(ROWS_SHIFT_OPEN, 1, 0, 0.0_dp, 0.0_dp, g%d, c_null_ptr, c_null_ptr, c_null_ptr, c_null_ptr, &
                             c_null_ptr, c, 0.0_dp, rows, g%n1)
            gmin = minval(rows); return
        end if
#endif
        call shift_open_cpu(g%h, c, gmin)
    end subroutine gcg_shift_open

    !> d = the combination `mode` (COMBINE_*) of a, b and the constants c1, c2, c3 (arrays a mode
    !> does not read may be any, d itself among them)
    subroutine gcg_combine(mode, d, a, b, c1, c2, c3)
        integer(c_int), intent(in) :: mode
        type(rarray_t), intent(inout) :: d
        type(rarray_t), intent(in) :: a, b
        real(dp), intent(in), optional :: c1, c2, c3
        real(dp) :: k(3)
        k = 0.0_dp
        if (present(c1)) k(1) = c1
        if (present(c2)) k(2) = c2
        if (present(c3)) k(3) = c3
#ifdef VESLIDE_CUDA
        if (d%device) then
            call combine_gpu(elements(d), mode, d%d, a%d, b%d, k(1), k(2), k(3)); return
        end if
#endif
        call combine_cpu(mode, d%h, a%h, b%h, k)
    end subroutine gcg_combine

    !> the least and the largest entry of a (this process's)
    subroutine gcg_extremes(a, amin, amax)
        type(rarray_t), intent(in) :: a
        real(dp), intent(out) :: amin, amax
#ifdef VESLIDE_CUDA
        real(dp) :: rows(2, a%n2)
        if (a%device) then
            call device_rows(ROWS_EXTREMES, 2, 0, 0.0_dp, 0.0_dp, a%d, c_null_ptr, c_null_ptr, c_null_ptr, c_null_ptr, &
                             c_null_ptr, 0.0_dp, 0.0_dp, rows, a%n1)
            amin = minval(rows(1, :)); amax = -minval(rows(2, :)); return
        end if
#endif
        amin = minval(a%h); amax = maxval(a%h)
    end subroutine gcg_extremes

#ifdef VESLIDE_CUDA
    !> rows(:, j) = the K values of row j of the pass `mode` on the device (K = size(rows, 1))
    subroutine device_rows(mode, k, law, s0, rho, a, b, c, d, free, edge, x1, x2, rows, nx)
        integer(c_int), intent(in) :: mode
        integer, intent(in) :: k, law, nx
        real(dp), intent(in) :: s0, rho, x1, x2
        type(c_ptr), intent(in) :: a, b, c, d, free, edge
        real(dp), intent(out) :: rows(:, :)
        real(dp), allocatable :: out(:)
        allocate (out(k*size(rows, 2)))
        call rows_gpu(mode, law, s0, rho, nx, size(rows, 2), a, b, c, d, free, edge, x1, x2, out)
        rows = reshape(out, [k, size(rows, 2)])
    end subroutine device_rows
#endif

    ! ---- CPU twins ------------------------------------------------------------------------


    subroutine attract_exponential(s0, rho, g, r, at, edge, rows)
        real(dp), intent(in) :: s0, rho, g(:, :), r(:, :)
        real(dp), intent(out) :: at(:, :)
        integer(int8), intent(out) :: edge(:, :)
        real(dp), intent(out) :: rows(:, :)
        integer :: i, j
        real(dp) :: s(2)
        !$omp parallel do schedule(static) if (threaded(size(g), size(g, 2))) private(i, s)
        do j = 1, size(g, 2)
            ! (a column at once: gfortran takes glibc's vector exp, as the array form before did;
            ! g >= 0 in the solve, so this is the law's map exponential_attraction)
            at(:, j) = r(:, j) + s0*exp(-g(:, j)/rho)
            s = 0.0_dp
            do i = 1, size(g, 1)
                edge(i, j) = 0_int8
                if (g(i, j) > 0.0_dp) then
                    s(1) = s(1) + at(i, j); s(2) = s(2) + 1.0_dp
                end if
            end do
            rows(1:2, j) = s; rows(3, j) = 0.0_dp
        end do
        !$omp end parallel do
    end subroutine attract_exponential

    subroutine attract_dugdale(s0, rho, g, r, at, edge, rows)
        real(dp), intent(in) :: s0, rho, g(:, :), r(:, :)
        real(dp), intent(out) :: at(:, :)
        integer(int8), intent(out) :: edge(:, :)
        real(dp), intent(out) :: rows(:, :)
        integer :: i, j
        real(dp) :: s(3)
        !$omp parallel do schedule(static) if (threaded(size(g), size(g, 2))) private(i, s)
        do j = 1, size(g, 2)
            s = 0.0_dp
            do i = 1, size(g, 1)
                at(i, j) = r(i, j) + dugdale_attraction(g(i, j), s0, rho)
                edge(i, j) = merge(1_int8, 0_int8, g(i, j) == rho)
                if (edge(i, j) == 1) then
                    s(3) = s(3) + 1.0_dp
                else if (g(i, j) > 0.0_dp) then
                    s(1) = s(1) + at(i, j); s(2) = s(2) + 1.0_dp
                end if
            end do
            rows(:, j) = s
        end do
        !$omp end parallel do
    end subroutine attract_dugdale

    subroutine free_set_cpu(g, r, at, free, edge, lam, s0, held, rows)
        real(dp), intent(in) :: g(:, :), r(:, :), lam, s0
        real(dp), intent(inout) :: at(:, :)
        integer(int8), intent(out) :: free(:, :)
        integer(int8), intent(in) :: edge(:, :)
        logical, intent(in) :: held
        real(dp), intent(out) :: rows(:, :)
        integer :: i, j
        real(dp) :: s(2)
        logical :: f
        !$omp parallel do schedule(static) if (threaded(size(g), size(g, 2))) private(i, s, f)
        do j = 1, size(g, 2)
            s = 0.0_dp
            do i = 1, size(g, 1)
                f = (g(i, j) > 0.0_dp .and. edge(i, j) == 0) .or. (g(i, j) <= 0.0_dp .and. at(i, j) - lam < 0.0_dp)
                if (held .and. edge(i, j) == 1) then
                    f = r(i, j) - lam > 0.0_dp .or. r(i, j) - lam < -s0
                    at(i, j) = r(i, j) + merge(s0, merge(0.0_dp, lam - r(i, j), r(i, j) - lam < -s0), r(i, j) - lam > 0.0_dp)
                end if
                free(i, j) = merge(1_int8, 0_int8, f)
                if (f) then
                    s(1) = s(1) + at(i, j); s(2) = s(2) + 1.0_dp
                end if
            end do
            rows(:, j) = s
        end do
        !$omp end parallel do
    end subroutine free_set_cpu

    subroutine centre_cpu(g, at, free, edge, lam, err)
        real(dp), intent(in) :: g(:, :), lam
        real(dp), intent(inout) :: at(:, :)
        integer(int8), intent(in) :: free(:, :), edge(:, :)
        real(dp), intent(out) :: err
        integer :: i, j
        real(dp) :: a
        err = 0.0_dp
        !$omp parallel do schedule(static) if (threaded(size(g), size(g, 2))) private(i, a) reduction(max:err)
        do j = 1, size(g, 2)
            do i = 1, size(g, 1)
                a = at(i, j) - lam
                if (edge(i, j) == 1 .and. free(i, j) == 0) a = 0.0_dp
                err = max(err, merge(abs(a), max(-a, 0.0_dp), g(i, j) > 0.0_dp))
                at(i, j) = merge(a, 0.0_dp, free(i, j) == 1)
            end do
        end do
        !$omp end parallel do
    end subroutine centre_cpu

    subroutine spectral_real_cpu(mode, k, ainv, c1, cells)
        integer(c_int), intent(in) :: mode
        complex(dp), intent(inout) :: k(:, :)
        real(dp), intent(in) :: ainv(:, :), c1, cells
        integer :: j
        !$omp parallel do schedule(static) if (threaded(2*size(k), size(k, 2)))
        do j = 1, size(k, 2)
            if (mode == SPECTRAL_A) then
                k(:, j) = k(:, j)*ainv(:, j)
            else
                where (ainv(:, j) /= 0.0_dp)
                    k(:, j) = k(:, j)/((ainv(:, j)*cells + c1)*cells)
                elsewhere
                    k(:, j) = (0.0_dp, 0.0_dp)
                end where
            end if
        end do
        !$omp end parallel do
    end subroutine spectral_real_cpu

    subroutine spectral_complex_cpu(mode, k, kinv, ainv, cells)
        integer(c_int), intent(in) :: mode
        complex(dp), intent(inout) :: k(:, :)
        complex(dp), intent(in) :: kinv(:, :)
        real(dp), intent(in) :: ainv(:, :), cells
        integer :: j
        !$omp parallel do schedule(static) if (threaded(2*size(k), size(k, 2)))
        do j = 1, size(k, 2)
            select case (mode)
            case (SPECTRAL_OPERATOR)
                k(:, j) = k(:, j)*kinv(:, j)
            case (SPECTRAL_RESOLVENT)
                where (kinv(:, j) /= (0.0_dp, 0.0_dp))
                    k(:, j) = k(:, j)/((1.0_dp + kinv(:, j)/ainv(:, j))*cells)
                elsewhere
                    k(:, j) = k(:, j)/cells
                end where
            case default
                where (kinv(:, j) /= (0.0_dp, 0.0_dp))
                    k(:, j) = k(:, j)*(kinv(:, j)/ainv(:, j))/cells
                elsewhere
                    k(:, j) = (0.0_dp, 0.0_dp)
                end where
            end select
        end do
        !$omp end parallel do
    end subroutine spectral_complex_cpu

    subroutine mask_cpu(a, free, rows)
        real(dp), intent(inout) :: a(:, :)
        integer(int8), intent(in) :: free(:, :)
        real(dp), intent(out) :: rows(:, :)
        integer :: i, j
        real(dp) :: s(2)
        !$omp parallel do schedule(static) if (threaded(size(a), size(a, 2))) private(i, s)
        do j = 1, size(a, 2)
            s = 0.0_dp
            do i = 1, size(a, 1)
                if (free(i, j) == 1) then
                    s(1) = s(1) + a(i, j); s(2) = s(2) + 1.0_dp
                else
                    a(i, j) = 0.0_dp
                end if
            end do
            rows(:, j) = s
        end do
        !$omp end parallel do
    end subroutine mask_cpu

    subroutine dot_cpu(a, b, rows)
        real(dp), intent(in) :: a(:, :), b(:, :)
        real(dp), intent(out) :: rows(:, :)
        integer :: i, j
        real(dp) :: s
        !$omp parallel do schedule(static) if (threaded(size(a), size(a, 2))) private(i, s)
        do j = 1, size(a, 2)
            s = 0.0_dp
            do i = 1, size(a, 1)
                s = s + a(i, j)*b(i, j)
            end do
            rows(1, j) = s
        end do
        !$omp end parallel do
    end subroutine dot_cpu

    subroutine shift_dot_cpu(a, b, free, c, rows)
        real(dp), intent(inout) :: a(:, :)
        real(dp), intent(in) :: b(:, :), c
        integer(int8), intent(in) :: free(:, :)
        real(dp), intent(out) :: rows(:, :)
        integer :: i, j
        real(dp) :: s
        !$omp parallel do schedule(static) if (threaded(size(a), size(a, 2))) private(i, s)
        do j = 1, size(a, 2)
            s = 0.0_dp
            do i = 1, size(a, 1)
                if (free(i, j) == 1) a(i, j) = a(i, j) - c
                s = s + b(i, j)*a(i, j)
            end do
            rows(1, j) = s
        end do
        !$omp end parallel do
    end subroutine shift_dot_cpu

    subroutine direction_cpu(z, at, t, free, beta, rows)
        real(dp), intent(in) :: z(:, :), at(:, :), beta
        real(dp), intent(inout) :: t(:, :)
        integer(int8), intent(in) :: free(:, :)
        real(dp), intent(out) :: rows(:, :)
        integer :: i, j
        real(dp) :: s
        !$omp parallel do schedule(static) if (threaded(size(t), size(t, 2))) private(i, s)
        do j = 1, size(t, 2)
            s = 0.0_dp
            do i = 1, size(t, 1)
                if (free(i, j) == 1) then
                    t(i, j) = z(i, j) + beta*t(i, j)
                else
                    t(i, j) = 0.0_dp
                end if
                s = s + at(i, j)*t(i, j)
            end do
            rows(1, j) = s
        end do
        !$omp end parallel do
    end subroutine direction_cpu

    subroutine curvature_cpu(pz, t, free, rows)
        real(dp), intent(in) :: pz(:, :), t(:, :)
        integer(int8), intent(in) :: free(:, :)
        real(dp), intent(out) :: rows(:, :)
        integer :: i, j
        real(dp) :: s(4)
        !$omp parallel do schedule(static) if (threaded(size(t), size(t, 2))) private(i, s)
        do j = 1, size(t, 2)
            s = 0.0_dp
            do i = 1, size(t, 1)
                if (free(i, j) == 1) then
                    s(1) = s(1) + pz(i, j)*t(i, j)
                    s(2) = s(2) + pz(i, j)
                    s(3) = s(3) + 1.0_dp
                    s(4) = s(4) + t(i, j)
                end if
            end do
            rows(:, j) = s
        end do
        !$omp end parallel do
    end subroutine curvature_cpu

    subroutine step_smooth(g, t, tau, rows, gmin)
        real(dp), intent(inout) :: g(:, :)
        real(dp), intent(in) :: t(:, :), tau
        real(dp), intent(out) :: rows(:, :), gmin
        integer :: i, j
        real(dp) :: v, c
        gmin = huge(1.0_dp)
        !$omp parallel do schedule(static) if (threaded(size(g), size(g, 2))) private(i, v, c) reduction(min:gmin)
        do j = 1, size(g, 2)
            c = 0.0_dp
            do i = 1, size(g, 1)
                v = g(i, j) - tau*t(i, j)
                gmin = min(gmin, v)
                if (v < 0.0_dp) c = c + 1.0_dp
                g(i, j) = max(v, 0.0_dp)
            end do
            rows(1, j) = 0.0_dp; rows(2, j) = c
        end do
        !$omp end parallel do
    end subroutine step_smooth

    subroutine step_dugdale(rho, g, t, tau, edge, rows, gmin)
        real(dp), intent(in) :: rho, t(:, :), tau
        real(dp), intent(inout) :: g(:, :)
        integer(int8), intent(out) :: edge(:, :)
        real(dp), intent(out) :: rows(:, :), gmin
        integer :: i, j
        real(dp) :: v, s, c
        logical :: below, stop_here
        gmin = huge(1.0_dp)
        !$omp parallel do schedule(static) if (threaded(size(g), size(g, 2))) &
        !$omp private(i, v, s, c, below, stop_here) reduction(min:gmin)
        do j = 1, size(g, 2)
            s = 0.0_dp; c = 0.0_dp
            do i = 1, size(g, 1)
                below = g(i, j) < rho
                v = g(i, j) - tau*t(i, j)
                gmin = min(gmin, v)
                if (v < 0.0_dp) c = c + 1.0_dp
                v = max(v, 0.0_dp)
                ! (the step's start g - (-tau t) from the clipped end, as the array form had it)
                stop_here = (below .and. v > rho) .or. (.not. below .and. v < rho .and. v - (-tau*t(i, j)) > rho)
                if (stop_here) then
                    v = rho; s = s + 1.0_dp
                end if
                g(i, j) = v
                edge(i, j) = merge(1_int8, 0_int8, stop_here)
            end do
            rows(1, j) = s; rows(2, j) = c
        end do
        !$omp end parallel do
    end subroutine step_dugdale

    subroutine gap_sums_cpu(g, clip, rows)
        real(dp), intent(inout) :: g(:, :)
        logical, intent(in) :: clip
        real(dp), intent(out) :: rows(:, :)
        integer :: i, j
        real(dp) :: s(2)
        !$omp parallel do schedule(static) if (threaded(size(g), size(g, 2))) private(i, s)
        do j = 1, size(g, 2)
            s = 0.0_dp
            do i = 1, size(g, 1)
                if (clip) g(i, j) = max(g(i, j), 0.0_dp)
                s(1) = s(1) + g(i, j)
                if (g(i, j) > 0.0_dp) s(2) = s(2) + 1.0_dp
            end do
            rows(:, j) = s
        end do
        !$omp end parallel do
    end subroutine gap_sums_cpu

    subroutine shift_open_cpu(g, c, gmin)
        real(dp), intent(inout) :: g(:, :)
        real(dp), intent(in) :: c
        real(dp), intent(out) :: gmin
        integer :: i, j
        gmin = huge(1.0_dp)
        !$omp parallel do schedule(static) if (threaded(size(g), size(g, 2))) private(i) reduction(min:gmin)
        do j = 1, size(g, 2)
            do i = 1, size(g, 1)
                if (g(i, j) > 0.0_dp) g(i, j) = g(i, j) + c
                gmin = min(gmin, g(i, j))
            end do
        end do
        !$omp end parallel do
    end subroutine shift_open_cpu

    subroutine combine_cpu(mode, d, a, b, k)
        integer(c_int), intent(in) :: mode
        real(dp), intent(inout) :: d(:, :)
        real(dp), intent(in) :: a(:, :), b(:, :), k(3)
        integer :: j
        !$omp parallel do schedule(static) if (threaded(size(d), size(d, 2)))
        do j = 1, size(d, 2)
            select case (mode)
            case (COMBINE_SUM)
                d(:, j) = a(:, j) + b(:, j)
            case (COMBINE_DIFFERENCE)
                d(:, j) = (a(:, j) - b(:, j)) - k(1)
            case (COMBINE_REFLECT)
                d(:, j) = a(:, j) - 2.0_dp*b(:, j)
            case (COMBINE_ACCUMULATE)
                d(:, j) = d(:, j) + k(1)*(a(:, j) - b(:, j))
            case (COMBINE_PRESSURE)
                d(:, j) = k(1) + k(2)*(a(:, j) - k(3))
            case (COMBINE_DISPLACEMENT)
                d(:, j) = k(2)*((a(:, j) + b(:, j)) - k(1))
            case (COMBINE_FROM)
                d(:, j) = k(1) - a(:, j)
            case default
                d(:, j) = d(:, j) - k(1)*a(:, j)
            end select
        end do
        !$omp end parallel do
    end subroutine combine_cpu

    include 'veslide_contact_law_maps.inc'

end module veslide_gcg_passes
