!> Statistics of real fields on a grid that may be distributed: sums, means, rms, dot products,
!> extrema and counts over the whole grid, the same on every process.
!>
!> Sums are taken row by row (each row added sequentially by one thread), then over the rows in
!> their global order (`ordered_sum`): the result does not depend on the number of threads or of
!> processes that hold the rows. A field is (nx, ny_local): the process's rows.
module veslide_fields
    use veslide_kinds, only: dp, i8
    use veslide_grid, only: grid_t
    use veslide_collective, only: ordered_sum, global_min, global_max, global_count
    use veslide_threads, only: threaded
    implicit none
    private
    public :: field_sum, field_mean, field_rms, field_dot, field_max, field_min, field_count, field_sums

contains

    !> Sum of f over the grid
    real(dp) function field_sum(grid, f) result(s)
        type(grid_t), intent(in) :: grid
        real(dp), intent(in) :: f(:, :)
        real(dp) :: rows(1, size(f, 2)), t(1)
        integer :: j
        !$omp parallel do schedule(guided) if (threaded(size(f), size(f, 2)))
        do j = 1, size(f, 2)
            rows(1, j) = sum(f(:, j))
        end do
        !$omp end parallel do
        call ordered_sum(grid, rows, t)
        s = t(1)
    end function field_sum

    !> Several sums at once, totals(k) = sum of f(:, :, k) (one collective instead of k)
    subroutine field_sums(grid, f, totals)
        type(grid_t), intent(in) :: grid
        real(dp), intent(in) :: f(:, :, :)
        real(dp), intent(out) :: totals(:)
        real(dp) :: rows(size(f, 3), size(f, 2))
        integer :: j, k
        !$omp parallel do schedule(guided) if (threaded(size(f), size(f, 2))) private(k)
        do j = 1, size(f, 2)
            do k = 1, size(f, 3)
                rows(k, j) = sum(f(:, j, k))
            end do
        end do
        !$omp end parallel do
        call ordered_sum(grid, rows, totals)
    end subroutine field_sums

    !> Mean of f over the grid
    real(dp) function field_mean(grid, f) result(m)
        type(grid_t), intent(in) :: grid
        real(dp), intent(in) :: f(:, :)
        m = field_sum(grid, f)/grid%cells()
    end function field_mean

    !> rms of f about its mean
    real(dp) function field_rms(grid, f) result(r)
        type(grid_t), intent(in) :: grid
        real(dp), intent(in) :: f(:, :)
        real(dp) :: rows(1, size(f, 2)), t(1), m
        integer :: j
        m = field_mean(grid, f)
        !$omp parallel do schedule(guided) if (threaded(size(f), size(f, 2)))
        do j = 1, size(f, 2)
            rows(1, j) = sum((f(:, j) - m)**2)
        end do
        !$omp end parallel do
        call ordered_sum(grid, rows, t)
        r = sqrt(t(1)/grid%cells())
    end function field_rms

    !> Sum of f g over the grid
    real(dp) function field_dot(grid, f, g) result(s)
        type(grid_t), intent(in) :: grid
        real(dp), intent(in) :: f(:, :), g(:, :)
        real(dp) :: rows(1, size(f, 2)), t(1)
        integer :: j
        !$omp parallel do schedule(guided) if (threaded(size(f), size(f, 2)))
        do j = 1, size(f, 2)
            rows(1, j) = sum(f(:, j)*g(:, j))
        end do
        !$omp end parallel do
        call ordered_sum(grid, rows, t)
        s = t(1)
    end function field_dot

    !> Largest value of f over the grid (-huge on an empty grid)
    real(dp) function field_max(grid, f) result(m)
        type(grid_t), intent(in) :: grid
        real(dp), intent(in) :: f(:, :)
        m = -huge(1.0_dp)
        if (size(f) > 0) m = maxval(f)
        call global_max(grid, m)
    end function field_max

    !> Smallest value of f over the grid (huge on an empty grid)
    real(dp) function field_min(grid, f) result(m)
        type(grid_t), intent(in) :: grid
        real(dp), intent(in) :: f(:, :)
        m = huge(1.0_dp)
        if (size(f) > 0) m = minval(f)
        call global_min(grid, m)
    end function field_min

    !> Number of true entries of mask over the grid
    integer(i8) function field_count(grid, mask) result(n)
        type(grid_t), intent(in) :: grid
        logical, intent(in) :: mask(:, :)
        integer(i8) :: a(1)
        a(1) = count(mask, kind=i8)
        call global_count(grid, a)
        n = a(1)
    end function field_count

end module veslide_fields
