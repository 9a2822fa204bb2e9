!> The passes of the splitting (veslide_solver_dr) besides its map and mixing (those are
!> Anderson's, veslide_anderson_passes, with the map fused in), on either backend: each a
!> dispatcher on the arrays' backend, its CPU twin here (`*_cpu`, on the fields flattened to
!> n = nx ny unknowns) and its CUDA twin in veslide_dr_passes.cu. The passes that apply the
!> contact law (y = prox(2x - z), the law's proximal map: the hard wall's max(2x - z, 0)) take it
!> and choose its maps once per call (one CPU twin per law; the CUDA functors take the law as a
!> template argument, vs::with_law).
!>  rebalance  z = y + s (z - y) (z remapped to a step s times larger); x = z
!>  project    p = p_mean y
!>  restore    z = z_prev + f_prev; x = z
!>  add_gap    z = z + gamma g/hs
!>  load_sums  per row the load prox(v - c) carries, sum(prox(v - c)), and the cells it puts in
!>             contact, v = 2x - z; the largest v
!>  shift      z = z + c
module veslide_dr_passes
    use, intrinsic :: iso_c_binding, only: c_ptr, c_int, c_double, c_long
    use veslide_kinds, only: dp
    use veslide_arrays, only: rarray_t, elements
    use veslide_contact_law, only: contact_law_t, LAW_HARD_WALL
    use veslide_threads, only: threaded
    implicit none
    private
    public :: dr_rebalance, dr_project, dr_restore, dr_add_gap, dr_load_sums, dr_shift

#ifdef VESLIDE_CUDA
    interface
        !> through the law's proximal map: mode 0: rebalance (s), 1: project (s = p_mean, into p)
        subroutine reflect_gpu(law, param, n, mode, x, z, p, s) bind(c, name='veslide_dr_reflect')
            import :: c_long, c_int, c_ptr, c_double
            integer(c_int), value :: law
            real(c_double), intent(in) :: param(*)
            integer(c_long), value :: n
            integer(c_int), value :: mode
            type(c_ptr), value :: x, z, p
            real(c_double), value :: s
        end subroutine reflect_gpu
        !> mode 2: restore, 3: add_gap (x = g, s = gamma/hs pair), 4: shift (z = z + s)
        subroutine elementwise_gpu(n, mode, x, z, p, a, b, s, t) bind(c, name='veslide_dr_elementwise')
            import :: c_long, c_int, c_ptr, c_double
            integer(c_long), value :: n
            integer(c_int), value :: mode
            type(c_ptr), value :: x, z, p, a, b
            real(c_double), value :: s, t
        end subroutine elementwise_gpu
        !> rows(3, ny): [sum prox(v - c), count of its contact cells, min -v], v = 2x - z
        subroutine load_sums_gpu(law, param, nx, ny, x, z, c, rows) bind(c, name='veslide_dr_load_sums')
            import :: c_int, c_ptr, c_double
            integer(c_int), value :: law
            real(c_double), intent(in) :: param(*)
            integer(c_int), value :: nx, ny
            type(c_ptr), value :: x, z
            real(c_double), value :: c
            real(c_double), intent(out) :: rows(*)
        end subroutine load_sums_gpu
    end interface
#endif

contains


    ! ---- dispatchers --------------------------------------------------------------------

    !> z = y + s (z - y), y = prox(2x - z) (the law's proximal map); x = z
    subroutine dr_rebalance(law, x, z, s)
        type(contact_law_t), intent(in) :: law
        type(rarray_t), intent(inout) :: x, z
        real(dp), intent(in) :: s
#ifdef VESLIDE_CUDA
        if (x%device) then
            call reflect_gpu(law%kind, law%param, elements(x), 0_c_int, x%d, z%d, z%d, s); return
        end if
#endif
        select case (law%kind)
        case (LAW_HARD_WALL)
            call dr_rebalance_hard_wall(elements(x), x%h, z%h, s)
        case default
            error stop "veslide:dr_passes:dr_rebalance: a contact law this pass does not take"
        end select
    end subroutine dr_rebalance

    !> p = p_mean prox(2x - z) (the law's proximal map)
    subroutine dr_project(law, p, x, z, p_mean)
        type(contact_law_t), intent(in) :: law
        type(rarray_t), intent(inout) :: p
        type(rarray_t), intent(in) :: x, z
        real(dp), intent(in) :: p_mean
#ifdef VESLIDE_CUDA
        if (p%device) then
            call reflect_gpu(law%kind, law%param, elements(p), 1_c_int, x%d, z%d, p%d, p_mean); return
        end if
#endif
        select case (law%kind)
        case (LAW_HARD_WALL)
            p%h = p_mean*hard_wall_project(2.0_dp*x%h - z%h)
        case default
            error stop "veslide:dr_passes:dr_project: a contact law this pass does not take"
        end select
    end subroutine dr_project

    !> z = z_prev + f_prev; x = z
    subroutine dr_restore(x, z, zprev, fprev)
        type(rarray_t), intent(inout) :: x, z
        type(rarray_t), intent(in) :: zprev, fprev
#ifdef VESLIDE_CUDA
        if (x%device) then
            call elementwise_gpu(elements(x), 2_c_int, x%d, z%d, z%d, zprev%d, fprev%d, 0.0_dp, 0.0_dp); return
        end if
#endif
        call dr_restore_cpu(elements(x), x%h, z%h, zprev%h, fprev%h)
    end subroutine dr_restore

    !> z = z + gamma g/hs
    subroutine dr_add_gap(z, g, gamma, hs)
        type(rarray_t), intent(inout) :: z
        type(rarray_t), intent(in) :: g
        real(dp), intent(in) :: gamma, hs
#ifdef VESLIDE_CUDA
        if (z%device) then
            call elementwise_gpu(elements(z), 3_c_int, g%d, z%d, z%d, z%d, z%d, gamma, hs); return
        end if
#endif
        z%h = z%h + gamma*g%h/hs
    end subroutine dr_add_gap

    !> v = 2x - z: rows(:, j) = [sum of prox(v - c), count of the contact cells prox(v - c) makes]
    !> over row j (the law's proximal map and contact; the hard wall: max(v - c, 0) and v > c);
    !> vmax = max v (this process's)
    subroutine dr_load_sums(law, x, z, c, rows, vmax)
        type(contact_law_t), intent(in) :: law
        type(rarray_t), intent(in) :: x, z
        real(dp), intent(in) :: c
        real(dp), intent(out) :: rows(:, :), vmax
#ifdef VESLIDE_CUDA
        real(dp), allocatable :: out(:, :)
        if (x%device) then
            allocate (out(3, x%n2))
            call load_sums_gpu(law%kind, law%param, x%n1, x%n2, x%d, z%d, c, out)
            rows = out(1:2, :); vmax = -minval(out(3, :))
            return
        end if
#endif
        select case (law%kind)
        case (LAW_HARD_WALL)
            call dr_load_sums_hard_wall(x%h, z%h, c, rows, vmax)
        case default
            error stop "veslide:dr_passes:dr_load_sums: a contact law this pass does not take"
        end select
    end subroutine dr_load_sums

    !> z = z + c
    subroutine dr_shift(z, c)
        type(rarray_t), intent(inout) :: z
        real(dp), intent(in) :: c
#ifdef VESLIDE_CUDA
        if (z%device) then
            call elementwise_gpu(elements(z), 4_c_int, z%d, z%d, z%d, z%d, z%d, c, 0.0_dp); return
        end if
#endif
        z%h = z%h + c
    end subroutine dr_shift

    ! ---- CPU twins (those of a law: one per law) -----------------------------------------

    subroutine dr_rebalance_hard_wall(n, xb, z, s)
        integer(c_long), intent(in) :: n
        real(dp), intent(inout) :: xb(n), z(n)
        real(dp), intent(in) :: s
        real(dp) :: yv
        integer :: i
        !$omp parallel do schedule(guided) if (threaded(int(n), 2)) private(yv)
        do i = 1, int(n)
            yv = hard_wall_project(2.0_dp*xb(i) - z(i))
            z(i) = yv + s*(z(i) - yv)
            xb(i) = z(i)
        end do
        !$omp end parallel do
    end subroutine dr_rebalance_hard_wall

    subroutine dr_restore_cpu(n, xb, z, zprev, fprev)
        integer(c_long), intent(in) :: n
        real(dp), intent(inout) :: xb(n), z(n)
        real(dp), intent(in) :: zprev(n), fprev(n)
        z = zprev + fprev
        xb = z
    end subroutine dr_restore_cpu

    subroutine dr_load_sums_hard_wall(x, z, c, rows, vmax)
        real(dp), intent(in) :: x(:, :), z(:, :)
        real(dp), intent(in) :: c
        real(dp), intent(out) :: rows(:, :), vmax
        real(dp) :: v, t(2)
        integer :: i, j
        vmax = -huge(1.0_dp)
        !$omp parallel do schedule(guided) if (threaded(size(x), size(x, 2))) private(i, v, t) reduction(max:vmax)
        do j = 1, size(x, 2)
            t = 0.0_dp
            do i = 1, size(x, 1)
                v = 2.0_dp*x(i, j) - z(i, j)
                if (hard_wall_in_contact_shifted(v, c)) then
                    t(1) = t(1) + hard_wall_project(v - c); t(2) = t(2) + 1.0_dp
                end if
                vmax = max(vmax, v)
            end do
            rows(:, j) = t
        end do
        !$omp end parallel do
    end subroutine dr_load_sums_hard_wall

    include 'veslide_contact_law_maps.inc'

end module veslide_dr_passes
