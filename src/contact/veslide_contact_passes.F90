!> The passes of the contact problem's residual (veslide_contact), on either backend: the CPU
!> twins here, the CUDA twins in veslide_contact_passes.cu (same arguments, device memory).
!>  - `gap_and_contact_sums`: g = u - (h - h_mean); per row the sum of g over the contact set
!>    (p > 0); the size of that set, and the largest g (for a problem with no contact);
!>  - `gap_measures`: g = g + d; per row sum(p g), sum(|p|), sum(p); the smallest g and p.
module veslide_contact_passes
    use, intrinsic :: iso_c_binding, only: c_ptr, c_int, c_double
    use veslide_kinds, only: dp, i8
    use veslide_arrays, only: rarray_t
    implicit none
    private
    public :: gap_and_contact_sums, gap_measures

#ifdef VESLIDE_CUDA
    interface
        !> rows(3, ny): [sum of g over p > 0, count of p > 0, min of -g]
        subroutine gap_and_contact_sums_gpu(nx, ny, u, h, h_mean, p, g, rows) &
            bind(c, name='veslide_contact_gap_and_contact_sums')
            import :: c_int, c_ptr, c_double
            integer(c_int), value :: nx, ny
            type(c_ptr), value :: u, h, p, g
            real(c_double), value :: h_mean
            real(c_double), intent(out) :: rows(*)
        end subroutine gap_and_contact_sums_gpu
        !> rows(5, ny): [sum p g, sum |p|, sum p, min g, min p]
        subroutine gap_measures_gpu(nx, ny, p, g, approach, rows) bind(c, name='veslide_contact_gap_measures')
            import :: c_int, c_ptr, c_double
            integer(c_int), value :: nx, ny
            type(c_ptr), value :: p, g
            real(c_double), value :: approach
            real(c_double), intent(out) :: rows(*)
        end subroutine gap_measures_gpu
    end interface
#endif

contains

    !> g = u - (h - h_mean); rows(j) = sum of g over the contact cells of row j; nc = the
    !> number of contact cells; gmax = max g (this process's)
    subroutine gap_and_contact_sums(u, h, h_mean, p, g, rows, nc, gmax)
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
            call gap_and_contact_sums_gpu(g%n1, g%n2, u%d, h%d, h_mean, p%d, g%d, out)
            rows = out(1, :); nc = nint(sum(out(2, :)), i8); gmax = -minval(out(3, :))
            return
        end if
#endif
        call gap_and_contact_sums_cpu(u%h, h%h, h_mean, p%h, g%h, rows, nc, gmax)
    end subroutine gap_and_contact_sums

    !> g = g + approach; rows(:, j) = [sum p g, sum |p|, sum p] of row j; the smallest g and p
    subroutine gap_measures(p, g, approach, rows, gmin, pmin)
        type(rarray_t), intent(in) :: p
        type(rarray_t), intent(inout) :: g
        real(dp), intent(in) :: approach
        real(dp), intent(out) :: rows(:, :), gmin, pmin
#ifdef VESLIDE_CUDA
        real(dp), allocatable :: out(:, :)
        if (g%device) then
            allocate (out(5, g%n2))
            call gap_measures_gpu(g%n1, g%n2, p%d, g%d, approach, out)
            rows = out(1:3, :); gmin = minval(out(4, :)); pmin = minval(out(5, :))
            return
        end if
#endif
        call gap_measures_cpu(p%h, g%h, approach, rows, gmin, pmin)
    end subroutine gap_measures

    subroutine gap_and_contact_sums_cpu(u, h, h_mean, p, g, rows, nc, gmax)
        real(dp), intent(in) :: u(:, :), h(:, :), p(:, :)
        real(dp), intent(out) :: g(:, :)
        real(dp), intent(in) :: h_mean
        real(dp), intent(out) :: rows(:)
        integer(i8), intent(out) :: nc
        real(dp), intent(out) :: gmax
        integer :: i, j
        real(dp) :: s
        nc = 0; gmax = -huge(1.0_dp)
        !$omp parallel do schedule(guided) private(i, s) reduction(+:nc) reduction(max:gmax)
        do j = 1, size(g, 2)
            s = 0.0_dp
            do i = 1, size(g, 1)
                g(i, j) = u(i, j) - (h(i, j) - h_mean)
                if (p(i, j) > 0.0_dp) then
                    nc = nc + 1; s = s + g(i, j)
                end if
                gmax = max(gmax, g(i, j))
            end do
            rows(j) = s
        end do
        !$omp end parallel do
    end subroutine gap_and_contact_sums_cpu

    subroutine gap_measures_cpu(p, g, approach, rows, gmin, pmin)
        real(dp), intent(in) :: p(:, :)
        real(dp), intent(inout) :: g(:, :)
        real(dp), intent(in) :: approach
        real(dp), intent(out) :: rows(:, :), gmin, pmin
        integer :: i, j
        real(dp) :: t(3)
        gmin = huge(1.0_dp); pmin = huge(1.0_dp)
        !$omp parallel do schedule(guided) private(i, t) reduction(min:gmin, pmin)
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
    end subroutine gap_measures_cpu

end module veslide_contact_passes
