!> Quantities derived from a contact solution: area, separation, the slope-force estimator.
!> (The exact tangential force of the discrete operator is the kernel's `tangential_force`.)
module veslide_analysis
    use veslide_kinds, only: dp
    use veslide_grid, only: grid_t
    use veslide_fftw, only: fft2d_t
    implicit none
    private
    public :: contact_area_fraction, contact_area_subcell, mean_separation, slope_force

contains

    !> Fraction of cells carrying pressure
    pure real(dp) function contact_area_fraction(p) result(a)
        real(dp), intent(in) :: p(:, :)
        a = real(count(p > 0.0_dp), dp)/real(size(p), dp)
    end function contact_area_fraction

    !> Contact area fraction to second order in the cell size. The contact boundary crosses every
    !> grid segment between a contact cell (p > 0) and a free one; the crossing is located from the
    !> local form of a smooth contact edge, p^2 ~ d (1 + c d) inside and g^(2/3) ~ s (1 + c s)
    !> outside (elastic and, at the scale of a cell, viscoelastic edges alike): the zero of the
    !> parabola through three values of g^(2/3) along the segment's line outside (the smooth side;
    !> it may fall up to half a cell inside the last contact centre, whose small pressure carries
    !> the grid's edge error), else of the one through p^2 inside, each falling back to the line
    !> through two values, or to the segment's midpoint where neither side has two values. The area
    !> is then the signed area of the polygons the crossings and the contact centres cut from
    !> every square of four neighbouring centres (marching squares). Cell counting errs by O(h)
    !> along the perimeter; this estimate by O(h^2) (docs/validation.md).
    pure real(dp) function contact_area_subcell(p, g) result(a)
        !> pressure and gap on the grid (p > 0 marks contact)
        real(dp), intent(in) :: p(:, :), g(:, :)
        integer :: nx, ny, i, j, c, c2, m
        integer, parameter :: ci(4) = [0, 1, 1, 0], cj(4) = [0, 0, 1, 1]
        real(dp) :: xs(8), ys(8), t
        logical :: inside(4)
        nx = size(p, 1); ny = size(p, 2)
        if (count(p > 0.0_dp) == 0) then
            a = 0.0_dp; return
        end if
        a = 0.0_dp
        do j = 1, ny
            do i = 1, nx
                do c = 1, 4
                    inside(c) = p(at(i + ci(c), nx), at(j + cj(c), ny)) > 0.0_dp
                end do
                if (all(inside)) then
                    a = a + 1.0_dp; cycle
                end if
                if (.not. any(inside)) cycle
                ! walk the square's corners counter-clockwise: inside corners and the crossings
                m = 0
                do c = 1, 4
                    c2 = modulo(c, 4) + 1
                    if (inside(c)) then
                        m = m + 1; xs(m) = ci(c); ys(m) = cj(c)
                    end if
                    if (inside(c) .neqv. inside(c2)) then
                        if (inside(c)) then
                            t = crossing(i + ci(c), j + cj(c), ci(c2) - ci(c), cj(c2) - cj(c))
                            m = m + 1; xs(m) = ci(c) + t*(ci(c2) - ci(c)); ys(m) = cj(c) + t*(cj(c2) - cj(c))
                        else
                            t = crossing(i + ci(c2), j + cj(c2), ci(c) - ci(c2), cj(c) - cj(c2))
                            m = m + 1; xs(m) = ci(c2) + t*(ci(c) - ci(c2)); ys(m) = cj(c2) + t*(cj(c) - cj(c2))
                        end if
                    end if
                end do
                ! signed (counter-clockwise) area: a crossing beyond the contact centre (the last
                ! contact cell lies outside the edge) takes area away
                a = a + 0.5_dp*sum(xs(1:m)*cshift(ys(1:m), 1) - cshift(xs(1:m), 1)*ys(1:m))
            end do
        end do
        a = a/(real(nx, dp)*ny)
    contains
        pure integer function at(k, n)
            integer, intent(in) :: k, n
            at = modulo(k - 1, n) + 1
        end function at
        !> Distance (in cells) from contact cell (i0, j0) to the boundary towards its free neighbour
        !> (i0 + di, j0 + dj)
        pure real(dp) function crossing(i0, j0, di, dj) result(off)
            integer, intent(in) :: i0, j0, di, dj
            real(dp) :: y(3), v
            integer :: mm, k
            real(dp) :: est
            integer :: nest
            est = 0.0_dp; nest = 0
            mm = 0
            do k = 1, 3
                if (p(at(i0 + k*di, nx), at(j0 + k*dj, ny)) > 0.0_dp) exit
                v = g(at(i0 + k*di, nx), at(j0 + k*dj, ny))
                if (.not. v > 0.0_dp) exit
                mm = mm + 1; y(mm) = v**(2.0_dp/3.0_dp)
            end do
            if (mm >= 2) then
                if (y(2) > y(1)) then
                    est = est + 1.0_dp + zero_near(y(1:mm), -y(1)/(y(2) - y(1))); nest = nest + 1
                end if
            end if
            mm = 0
            do k = 0, 2
                v = p(at(i0 - k*di, nx), at(j0 - k*dj, ny))
                if (.not. v > 0.0_dp) exit
                mm = mm + 1; y(mm) = v**2
            end do
            if (mm >= 2) then
                if (y(2) > y(1)) then
                    est = est - zero_near(y(1:mm), -y(1)/(y(2) - y(1))); nest = nest + 1
                end if
            end if
            off = 0.5_dp
            if (nest > 0) off = min(max(est/nest, -0.5_dp), 1.0_dp)
        end function crossing
    end function contact_area_subcell

    !> The zero, nearest to the straight-line zero k1, of the polynomial through y(1..m) at
    !> k = 0, 1, (2) (a line for m = 2, a parabola for m = 3)
    pure real(dp) function zero_near(y, k1) result(k0)
        real(dp), intent(in) :: y(:), k1
        real(dp) :: c0, c1, c2, disc, r1, r2
        k0 = k1
        if (size(y) < 3) return
        c2 = 0.5_dp*(y(3) - 2.0_dp*y(2) + y(1)); c1 = y(2) - y(1) - c2; c0 = y(1)
        if (abs(c2) <= 1.0e-12_dp*abs(c1)) return
        disc = c1*c1 - 4.0_dp*c2*c0
        if (disc < 0.0_dp) return
        r1 = (-c1 + sqrt(disc))/(2.0_dp*c2); r2 = (-c1 - sqrt(disc))/(2.0_dp*c2)
        k0 = merge(r1, r2, abs(r1 - k1) <= abs(r2 - k1))
        if (abs(k0 - k1) > 0.5_dp) k0 = k1              ! a parabola far from the line: keep the line
    end function zero_near

    !> Mean gap over the whole cell (zero in contact) [m]
    pure real(dp) function mean_separation(g) result(s)
        real(dp), intent(in) :: g(:, :)
        s = sum(g)/real(size(g), dp)
    end function mean_separation

    !> The estimator <p grad h> [Pa] (in contact grad w = grad h); spectral derivative of h.
    !> Converges to the kernel's `tangential_force` under refinement; reported as a check.
    subroutine slope_force(grid, fft, p, h, f)
        type(grid_t), intent(in) :: grid
        type(fft2d_t), intent(inout) :: fft
        real(dp), intent(in) :: p(:, :), h(:, :)
        real(dp), intent(out) :: f(2)
        complex(dp), allocatable :: hk(:, :)
        integer :: i, j, d
        real(dp) :: q(2)
        fft%x = h
        call fft%forward()
        hk = fft%k
        do d = 1, 2
            do j = 1, grid%ny
                do i = 1, grid%nq()
                    q = grid%derivative_wavevector(i, j)
                    fft%k(i, j) = cmplx(0.0_dp, q(d), dp)*hk(i, j)
                end do
            end do
            call fft%backward()
            f(d) = sum(p*fft%x)/grid%cells()
        end do
    end subroutine slope_force

end module veslide_analysis
