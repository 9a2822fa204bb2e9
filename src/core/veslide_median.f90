!> The median of a sample (the benchmarks quote medians of repeated timings)
module veslide_median
    use veslide_kinds, only: dp
    implicit none
    private
    public :: median

contains

    !> Median of x (the mean of the two middle values for an even count); x is not changed
    pure real(dp) function median(x) result(m)
        real(dp), intent(in) :: x(:)
        real(dp) :: y(size(x)), tmp
        integer :: i, j
        y = x
        do i = 2, size(y)           ! insertion sort: samples are short
            tmp = y(i); j = i - 1
            do while (j >= 1)
                if (y(j) <= tmp) exit
                y(j + 1) = y(j); j = j - 1
            end do
            y(j + 1) = tmp
        end do
        m = 0.5_dp*(y((size(y) + 1)/2) + y(size(y)/2 + 1))
    end function median

end module veslide_median
