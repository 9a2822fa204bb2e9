!> The passes of the contact problem's residual (veslide_contact) and of its law alone
!> (veslide_contact_law), on either backend: the CPU twins here, the CUDA twins in
!> veslide_contact_passes.cu (same arguments, device memory). Each takes the contact law and
!> chooses its maps once per call: a `select case` on the law's kind around the loop over cells
!> (one CPU twin per law), a template argument of the functor in the CUDA twins (`vs::with_law`).
!>  - `gap_and_contact_sums`: g = u - (h - h_mean); per row the sum of g over the contact set
!>    (the law's contact); the size of that set, and the largest g (for a problem with no contact);
!>  - `gap_measures`: g = g + d; per row the sums the law's measures take (the hard wall:
!>    sum(p g), sum(|p|), sum(p)); the smallest g and p;
!>  - `project_and_sum`: a field made admissible by the law's proximal map (a solver's start:
!>    the hard wall clips it at zero), and its row sums;
!>  - `adhesive_measures`: an adhesive law's candidate (veslide_contact's adhesive_residuals):
!>    the fresh gap, the repulsive pressure at the solver's gap, per row the sum of p, and the
!>    extremes the law's measures take; the gap kept.
module veslide_contact_passes
    use, intrinsic :: iso_c_binding, only: c_ptr, c_int, c_double
    use veslide_kinds, only: dp, i8
    use veslide_arrays, only: rarray_t
    use veslide_contact_law, only: contact_law_t, LAW_HARD_WALL, LAW_EXPONENTIAL, LAW_DUGDALE
    use veslide_threads, only: threaded
    implicit none
    private
    public :: gap_and_contact_sums, gap_measures, project_and_sum, adhesive_measures

#ifdef VESLIDE_CUDA
    interface
        !> rows(3, ny): [sum of g over the contact set, its size, min of -g]
        subroutine gap_and_contact_sums_gpu(law, param, nx, ny, u, h, h_mean, p, g, rows) &
            bind(c, name='veslide_contact_gap_and_contact_sums')
            import :: c_int, c_ptr, c_double
            integer(c_int), value :: law, nx, ny
            real(c_double), intent(in) :: param(*)
            type(c_ptr), value :: u, h, p, g
            real(c_double), value :: h_mean
            real(c_double), intent(out) :: rows(*)
        end subroutine gap_and_contact_sums_gpu
        !> rows(5, ny): [sum p g, sum |p|, sum p, min g, min p]
        subroutine gap_measures_gpu(law, param, nx, ny, p, g, approach, rows) &
            bind(c, name='veslide_contact_gap_measures')
            import :: c_int, c_ptr, c_double
            integer(c_int), value :: law, nx, ny
            real(c_double), intent(in) :: param(*)
            type(c_ptr), value :: p, g
            real(c_double), value :: approach
            real(c_double), intent(out) :: rows(*)
        end subroutine gap_measures_gpu
        !> rows(ny): the row sums of the projected field
        !> rows(5, ny): [sum p, min g, min -|g - g_s|, min p_rep, min -c]
        subroutine adhesive_measures_gpu(law, param, nx, ny, u, h, h_mean, p, g, approach, p_scale, hs, rows) &
            bind(c, name='veslide_contact_adhesive_measures')
            import :: c_int, c_ptr, c_double
            integer(c_int), value :: law, nx, ny
            real(c_double), intent(in) :: param(*)
            type(c_ptr), value :: u, h, p, g
            real(c_double), value :: h_mean, approach, p_scale, hs
            real(c_double), intent(out) :: rows(*)
        end subroutine adhesive_measures_gpu
        subroutine project_and_sum_gpu(law, param, nx, ny, a, rows) bind(c, name='veslide_contact_project_and_sum')
            import :: c_int, c_ptr, c_double
            integer(c_int), value :: law, nx, ny
            real(c_double), intent(in) :: param(*)
            type(c_ptr), value :: a
            real(c_double), intent(out) :: rows(*)
        end subroutine project_and_sum_gpu
    end interface
#endif

contains

    ! ---- dispatchers --------------------------------------------------------------------

    !> g = u - (h - h_mean); rows(j) = sum of g over the contact cells of row j; nc = the
    !> number of contact cells; gmax = max g (this process's)
    subroutine gap_and_contact_sums(law, u, h, h_mean, p, g, rows, nc, gmax)
        type(contact_law_t), intent(in) :: law
        type(rarray_t), intent(in) :: u, h, p
        type(rarray_t), intent(inout) :: g
        real(dp), intent(in) :: h_mean
        real(dp), intent(out) :: rows(:)
        integer(i8), intent(out) :: nc
        real(dp), intent(out) :: gmax
#ifdef VESLIDE_CUDA
        real(dp), allocatable :: out(:, :)
        if (g%device) then
            allocate (out(3, g%n2))
            call gap_and_contact_sums_gpu(law%kind, law%param, g%n1, g%n2, u%d, h%d, h_mean, p%d, g%d, out)
            rows = out(1, :); nc = nint(sum(out(2, :)), i8); gmax = -minval(out(3, :))
            return
        end if
#endif
        select case (law%kind)
        case (LAW_HARD_WALL)
            call gap_and_contact_sums_hard_wall(u%h, h%h, h_mean, p%h, g%h, rows, nc, gmax)
        case default
            error stop "veslide:contact_passes:gap_and_contact_sums: a contact law this pass does not take"
        end select
    end subroutine gap_and_contact_sums

    !> g = g + approach; rows(:, j) = the sums of row j the law's measures take (the hard wall:
    !> [sum p g, sum |p|, sum p]); the smallest g and p
    subroutine gap_measures(law, p, g, approach, rows, gmin, pmin)
        type(contact_law_t), intent(in) :: law
        type(rarray_t), intent(in) :: p
        type(rarray_t), intent(inout) :: g
        real(dp), intent(in) :: approach
        real(dp), intent(out) :: rows(:, :), gmin, pmin
#ifdef VESLIDE_CUDA
        real(dp), allocatable :: out(:, :)
        if (g%device) then
            allocate (out(5, g%n2))
            call gap_measures_gpu(law%kind, law%param, g%n1, g%n2, p%d, g%d, approach, out)
            rows = out(1:3, :); gmin = minval(out(4, :)); pmin = minval(out(5, :))
            return
        end if
#endif
        select case (law%kind)
        case (LAW_HARD_WALL)
            call gap_measures_hard_wall(p%h, g%h, approach, rows, gmin, pmin)
        case default
            error stop "veslide:contact_passes:gap_measures: a contact law this pass does not take"
        end select
    end subroutine gap_measures

    !> a = the law's proximal map of a, cell by cell (the hard wall: max(a, 0)); rows(j) = the sum
    !> of row j
    subroutine project_and_sum(law, a, rows)
        type(contact_law_t), intent(in) :: law
        type(rarray_t), intent(inout) :: a
        real(dp), intent(out) :: rows(:)
#ifdef VESLIDE_CUDA
        if (a%device) then
            call project_and_sum_gpu(law%kind, law%param, a%n1, a%n2, a%d, rows); return
        end if
#endif
        select case (law%kind)
        case (LAW_HARD_WALL)
            call project_and_sum_hard_wall(a%h, rows)
        case default
            error stop "veslide:contact_passes:project_and_sum: a contact law this pass does not take"
        end select
    end subroutine project_and_sum

    !> An adhesive law's candidate: p with u = K p, the solver's gap g_s in g [m] (its closed
    !> cells exactly 0) and the approach. The fresh gap g = u - (h - h_mean) + approach and the
    !> repulsive pressure p_rep = p + sigma(g_s) (Dugdale's edge g_s = rho: the attraction in
    !> [0, sigma0] nearest to balancing p, contact_law_t%repulsive); rows(j) = the sum of p over
    !> row j; ext = [min(min g, -max |g - g_s|), min p_rep] and c = max min(|p_rep|/p_scale,
    !> max(g, 0)/hs) (this process's); g = 0 where g_s <= 0, else max(g, 0)
    subroutine adhesive_measures(law, u, h, h_mean, p, g, approach, p_scale, hs, rows, ext, c)
        type(contact_law_t), intent(in) :: law
        type(rarray_t), intent(in) :: u, h, p
        type(rarray_t), intent(inout) :: g
        real(dp), intent(in) :: h_mean, approach, p_scale, hs
        real(dp), intent(out) :: rows(:), ext(2), c
#ifdef VESLIDE_CUDA
        real(dp), allocatable :: out(:, :)
        if (g%device) then
            allocate (out(5, g%n2))
            call adhesive_measures_gpu(law%kind, law%param, g%n1, g%n2, u%d, h%d, h_mean, p%d, g%d, approach, p_scale, &
                                       hs, out)
            rows = out(1, :)
            ext = [min(minval(out(2, :)), minval(out(3, :))), minval(out(4, :))]
            c = -minval(out(5, :))
            return
        end if
#endif
        select case (law%kind)
        case (LAW_EXPONENTIAL, LAW_DUGDALE)
            call adhesive_measures_cpu(law, u%h, h%h, h_mean, p%h, g%h, approach, p_scale, hs, rows, ext, c)
        case default
            error stop "veslide:contact_passes:adhesive_measures: a contact law this pass does not take"
        end select
    end subroutine adhesive_measures

    ! ---- CPU twins, one per law ---------------------------------------------------------

    !> (the array expressions it replaced, row by row: the same bits)
    subroutine adhesive_measures_cpu(law, u, h, h_mean, p, g, approach, p_scale, hs, rows, ext, c)
        type(contact_law_t), intent(in) :: law
        real(dp), intent(in) :: u(:, :), h(:, :), p(:, :), h_mean, approach, p_scale, hs
        real(dp), intent(inout) :: g(:, :)
        real(dp), intent(out) :: rows(:), ext(2), c
        real(dp) :: gf(size(g, 1)), prep(size(g, 1), 1), e1, e2, e3, cm
        integer :: j
        e1 = huge(1.0_dp); e2 = huge(1.0_dp); e3 = huge(1.0_dp); cm = -huge(1.0_dp)
        !$omp parallel do schedule(static) if (threaded(size(g), size(g, 2))) &
        !$omp& private(gf, prep) reduction(min:e1, e2, e3) reduction(max:cm)
        do j = 1, size(g, 2)
            gf = u(:, j) - (h(:, j) - h_mean) + approach
            prep = law%repulsive(p(:, j:j), g(:, j:j))
            rows(j) = sum(p(:, j))
            e1 = min(e1, minval(gf)); e2 = min(e2, -maxval(abs(gf - g(:, j)))); e3 = min(e3, minval(prep))
            cm = max(cm, maxval(min(abs(prep(:, 1))/p_scale, max(gf, 0.0_dp)/hs)))
            where (g(:, j) <= 0.0_dp)
                g(:, j) = 0.0_dp
            elsewhere
                g(:, j) = max(gf, 0.0_dp)
            end where
        end do
        !$omp end parallel do
        ext = [min(e1, e2), e3]
        c = cm
    end subroutine adhesive_measures_cpu

    subroutine gap_and_contact_sums_hard_wall(u, h, h_mean, p, g, rows, nc, gmax)
        real(dp), intent(in) :: u(:, :), h(:, :), p(:, :)
        real(dp), intent(out) :: g(:, :)
        real(dp), intent(in) :: h_mean
        real(dp), intent(out) :: rows(:)
        integer(i8), intent(out) :: nc
        real(dp), intent(out) :: gmax
        integer :: i, j
        real(dp) :: s
        nc = 0; gmax = -huge(1.0_dp)
        !$omp parallel do schedule(guided) if (threaded(size(g), size(g, 2))) private(i, s) reduction(+:nc) reduction(max:gmax)
        do j = 1, size(g, 2)
            s = 0.0_dp
            do i = 1, size(g, 1)
                g(i, j) = u(i, j) - (h(i, j) - h_mean)
                if (hard_wall_in_contact(p(i, j))) then
                    nc = nc + 1; s = s + g(i, j)
                end if
                gmax = max(gmax, g(i, j))
            end do
            rows(j) = s
        end do
        !$omp end parallel do
    end subroutine gap_and_contact_sums_hard_wall

    subroutine gap_measures_hard_wall(p, g, approach, rows, gmin, pmin)
        real(dp), intent(in) :: p(:, :)
        real(dp), intent(inout) :: g(:, :)
        real(dp), intent(in) :: approach
        real(dp), intent(out) :: rows(:, :), gmin, pmin
        integer :: i, j
        real(dp) :: t(3)
        gmin = huge(1.0_dp); pmin = huge(1.0_dp)
        !$omp parallel do schedule(guided) if (threaded(size(g), size(g, 2))) private(i, t) reduction(min:gmin, pmin)
        do j = 1, size(g, 2)
            t = 0.0_dp
            do i = 1, size(g, 1)
                g(i, j) = g(i, j) + approach
                t(1) = t(1) + p(i, j)*g(i, j)
                t(2) = t(2) + abs(p(i, j))
                t(3) = t(3) + p(i, j)
                gmin = min(gmin, g(i, j)); pmin = min(pmin, p(i, j))
            end do
            rows(:, j) = t
        end do
        !$omp end parallel do
    end subroutine gap_measures_hard_wall

    subroutine project_and_sum_hard_wall(a, rows)
        real(dp), intent(inout) :: a(:, :)
        real(dp), intent(out) :: rows(:)
        integer :: j
        !$omp parallel do schedule(static) if (threaded(size(a), size(a, 2)))
        do j = 1, size(a, 2)
            a(:, j) = hard_wall_project(a(:, j))
        end do
        !$omp end parallel do
        !$omp parallel do schedule(guided) if (threaded(size(a), size(a, 2)))
        do j = 1, size(a, 2)
            rows(j) = sum(a(:, j))
        end do
        !$omp end parallel do
    end subroutine project_and_sum_hard_wall

    include 'veslide_contact_law_maps.inc'

end module veslide_contact_passes
