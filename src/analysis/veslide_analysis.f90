!> Quantities derived from a contact solution: area, separation, the slope-force estimator.
!> (The exact tangential force of the discrete operator is the kernel's `tangential_force`.)
!> What counts as contact is the contact law's (veslide_contact_law; the hard wall by default:
!> the cells that carry pressure).
module veslide_analysis
    use veslide_kinds, only: dp
    use veslide_grid, only: grid_t
    use veslide_fftw, only: fft2d_t
    use veslide_collective, only: ordered_sum, halo_rows
    use veslide_fields, only: field_count, field_mean, field_dot
    use veslide_contact_law, only: contact_law_t
    implicit none
    private
    public :: contact_area_fraction, contact_area_subcell, mean_separation, slope_force

contains

    !> Fraction of cells in contact (the law's contact cells of the pressure `p`: those carrying
    !> pressure, for the hard wall); over the whole grid when `grid` is given (the process's rows
    !> of a distributed grid)
    real(dp) function contact_area_fraction(p, grid, law, g) result(a)
        real(dp), intent(in) :: p(:, :)
        type(grid_t), intent(in), optional :: grid
        !> the contact law (default: the hard wall)
        type(contact_law_t), intent(in), optional :: law
        !> the gap, which an adhesive law's contact needs (veslide_contact_law)
        real(dp), intent(in), optional :: g(:, :)
        type(contact_law_t) :: law_
        if (present(law)) law_ = law
        if (present(grid)) then
            a = real(field_count(grid, law_%contact(p, g)), dp)/grid%cells()
        else
            a = real(count(law_%contact(p, g)), dp)/real(size(p), dp)
        end if
    end function contact_area_fraction

    !> Contact area fraction with the edge located within a cell. The contact boundary crosses every
    !> grid segment between a contact cell (the law's: p > 0 for the hard wall) and a free one;
    !> the crossing is located from the local form of a smooth contact edge, p^2 ~ d (1 + c d)
    !> inside and g^(2/3) ~ s (1 + c s) outside (elastic and, at the scale of a cell, viscoelastic edges alike): the mean of the zero
    !> of the parabola through three values of g^(2/3) along the segment's line outside and of the
    !> one through p^2 inside, each falling back to the line through two values, or the segment's
    !> midpoint where neither side has two values; kept between half a cell inside the last
    !> contact centre (whose small pressure carries the grid's edge error) and the free one. The area
    !> is then the signed area of the polygons the crossings and the contact centres cut from
    !> every square of four neighbouring centres (marching squares). Cell counting misplaces the
    !> edge by 0.1-0.2 cell; this estimate by at most 0.03 cell on the solver's fields (first order
    !> still, the error depending on where the edge falls in its cell) and to second order on fields
    !> with the exact edge asymptotics (docs/validation.md). With `grid`, over the
    !> whole grid (a distributed grid's neighbouring rows come from the other processes).
    real(dp) function contact_area_subcell(p, g, grid, law) result(a)
        !> pressure and gap on the grid (the law's contact cells of p mark contact)
        real(dp), intent(in) :: p(:, :), g(:, :)
        type(grid_t), intent(in), optional :: grid
        !> the contact law (default: the hard wall)
        type(contact_law_t), intent(in), optional :: law
        integer, parameter :: depth = 4       ! rows a square's crossings look beyond its own
        real(dp), allocatable :: pe(:, :), ge(:, :)
        logical, allocatable :: ce(:, :)
        real(dp) :: rows(1, size(p, 2)), t(1)
        type(grid_t) :: serial
        type(contact_law_t) :: law_
        integer :: nx, j
        nx = size(p, 1)
        if (present(law)) law_ = law
        if (present(grid)) then
            call halo_rows(grid, p, depth, pe); call halo_rows(grid, g, depth, ge)
        else
            serial%nx = nx; serial%ny = size(p, 2)       ! one process: periodic rows
            call halo_rows(serial, p, depth, pe); call halo_rows(serial, g, depth, ge)
        end if
        allocate (ce(size(pe, 1), lbound(pe, 2):ubound(pe, 2)))
        ce = law_%contact(pe, ge)
        !$omp parallel do schedule(guided)
        do j = 1, size(p, 2)
            rows(1, j) = subcell_row(pe, ge, ce, j, depth)
        end do
        !$omp end parallel do
        if (present(grid)) then
            call ordered_sum(grid, rows, t)
            a = t(1)/grid%cells()
        else
            a = 0.0_dp
            do j = 1, size(p, 2)
                a = a + rows(1, j)
            end do
            a = a/(real(nx, dp)*size(p, 2))
        end if
    end function contact_area_subcell

    !> Area (in cells) cut from the squares whose lower-left centre lies in row j of the extended
    !> fields p, g and contact cells c (rows 1-depth .. n+depth; periodic along x)
    pure real(dp) function subcell_row(p, g, c_in, j, depth) result(a)
        integer, intent(in) :: j, depth
        real(dp), intent(in) :: p(:, 1 - depth:), g(:, 1 - depth:)
        logical, intent(in) :: c_in(:, 1 - depth:)
        integer :: nx, i, c, c2, m
        integer, parameter :: ci(4) = [0, 1, 1, 0], cj(4) = [0, 0, 1, 1]
        real(dp) :: xs(8), ys(8), t
        logical :: inside(4)
        nx = size(p, 1)
        a = 0.0_dp
        do i = 1, nx
            do c = 1, 4
                inside(c) = c_in(at(i + ci(c)), j + cj(c))
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
    contains
        pure integer function at(k)
            integer, intent(in) :: k
            at = modulo(k - 1, nx) + 1
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
                if (c_in(at(i0 + k*di), j0 + k*dj)) exit
                v = g(at(i0 + k*di), j0 + k*dj)
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
                if (.not. c_in(at(i0 - k*di), j0 - k*dj)) exit
                v = p(at(i0 - k*di), j0 - k*dj)
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
    end function subcell_row

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

    !> Mean gap over the whole cell (zero in contact) [m] (over the whole grid when `grid` is given)
    real(dp) function mean_separation(g, grid) result(s)
        real(dp), intent(in) :: g(:, :)
        type(grid_t), intent(in), optional :: grid
        if (present(grid)) then
            s = field_mean(grid, g)
        else
            s = sum(g)/real(size(g), dp)
        end if
    end function mean_separation

    !> The estimator <p grad h> [Pa] (in contact grad w = grad h); spectral derivative of h.
    !> Converges to the kernel's `tangential_force` under refinement; reported as a check.
    subroutine slope_force(grid, fft, p, h, f)
        type(grid_t), intent(in) :: grid
        type(fft2d_t), intent(inout) :: fft
        real(dp), intent(in) :: p(:, :), h(:, :)
        real(dp), intent(out) :: f(2)
        complex(dp), allocatable :: hk(:, :)
        integer :: a, b, d, ij(2)
        real(dp) :: q(2)
        fft%x = h
        call fft%forward()
        hk = fft%k
        do d = 1, 2
            do b = 1, size(hk, 2)
                do a = 1, size(hk, 1)
                    ij = grid%spectral_index(a, b)
                    q = grid%derivative_wavevector(ij(1), ij(2))
                    fft%k(a, b) = cmplx(0.0_dp, q(d), dp)*hk(a, b)
                end do
            end do
            call fft%backward()
            f(d) = field_dot(grid, p, fft%x)/grid%cells()
        end do
    end subroutine slope_force

end module veslide_analysis
