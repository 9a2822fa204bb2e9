!> The trailing edges of a sliding adhesive contact: the energy release rate of each edge where the
!> gap opens as the solid leaves the contact (docs/adhesion.md, *Trailing edges*).
!>
!> Relative to the rigid surface the solid's material moves along -v: it enters a contact at the
!> contact's leading edge (its +v side) and leaves it at the trailing edge (its -v side), where the
!> gap opens like a crack that runs into the bonded solid at the speed v. The energy release rate
!> of that crack as its far field sees it is G = K^2/(2 E0*), E0 the relaxed modulus: w at rest,
!> rising with speed toward (Einf/E0) w (Persson and Brener, PRE 71 (2005) 036123; with a cohesive
!> zone, Schapery's and Greenwood's steady-crack analyses). It is measured here without K, as the
!> J integral of the relaxed solid over the edge's cohesive zone:
!>   G = integral of sigma(g) d(g + Delta - P)
!> from the edge's last closed cell along -v over the open cells, until the law's energy V(g) has
!> risen to -1e-3 w (the rest of the attraction, -V, added at the last step's d ghat/d g; a walk
!> that meets the next closed cell first is not measured). Delta = u0 - u is the
!> relaxed solid's misfit: u0 the displacement the solid at rest (the kernel at zero speed) would
!> have under the case's traction, u the solid's own. P is the cubic fitted (least squares) to
!> Delta over the contact's cells behind the edge, up to `fit_cells` of them: the misfit is smooth
!> on the contact side of an opening edge (the material there has been in contact a while), and P
!> continues it across the edge, so that g + Delta - P is the relaxed solid's opening (a window of
!> 64 to 256 cells moved the steady crack's G by 0.1 % and took the glassy limit from 10.002 to
!> 10.04 w against Einf/E0 = 10, the window then spanning the wave's curvature). Between
!> neighbouring cells the integral is (d ghat/d g) (V(g_b) - V(g_a)), exact where ghat is linear
!> in g: an elastic solid (Delta = 0) gives exactly w at every edge.
!>
!> An edge is measured when at least 16 contact cells lie behind it, at least `crack` (4) times the
!> cohesive zone its G makes (a0 G/w, a0 = pi E0* w/(4 sigma0^2) the zone at rest: the zone grows
!> with K^2), its attraction is spent before the next closed cell, and its release is positive:
!> else it is not an opening crack's edge (a long range's zone as wide as the contact read
!> 10.37 w against Einf/E0 = 10 glassy).
!>
!> The closing (leading) edge has no measure of this form: the material there has just entered
!> the contact, and its misfit changes over v tau from the edge, so no fit on the contact side
!> continues it (docs/adhesion.md measures how far such fits spread).
!>
!> A line contact only: a profile of one row sliding along x, or of one column sliding along y
!> (else NaN). The integral along the line is the J integral of a straight edge uniform across
!> the motion. On a two-dimensional contact the edges are curved fronts of finite length among
!> other patches, whose misfit varies along the walk: on the paper scene (512^2, range 0.5 um) the
!> line integral read 1.34 w slow and -8 to -60 w in motion, no energy release rate. A column on a
!> grid distributed over processes is not measured either (each holds whole rows). Sums in order
!> (veslide_collective): the same for any number of threads or processes.
module veslide_edges
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use veslide_kinds, only: dp
    use veslide_grid, only: grid_t
    use veslide_contact_law, only: contact_law_t, ADH_ENERGY
    use veslide_collective, only: ordered_sum
    use veslide_lapack, only: dgels
    implicit none
    private
    public :: trailing_edge_energy, edges_measured

    !> the most contact cells behind an edge that the misfit's polynomial is fitted to
    integer, parameter :: fit_cells = 32
    !> the walk stops where the law's energy has risen above -spent w (the rest, -V(g_end), added at
    !> the last step's d ghat/d g); an edge whose walk meets a closed cell first is not measured
    real(dp), parameter :: spent = 1.0e-3_dp
    !> an edge is measured when at least this many closed cells lie behind it, and at least
    !> `crack` times the cohesive zone its G makes (a0 G/w, a0 the zone at rest)
    integer, parameter :: fit_min = 16
    real(dp), parameter :: crack = 4.0_dp

contains

    !> The mean energy release rate `energy` [J/m^2] over the trailing edges of the closed cells of
    !> the gap `g` [m] (an adhesive law's), and the number of edges `edges`, for a motion at
    !> `direction_rad` from x; `delta` [m] is the relaxed solid's misfit u0 - u (zero for an elastic
    !> solid or at rest), `zone` [m] the law's cohesive zone at rest, pi E0* w/(4 sigma0^2). NaN
    !> (and no edge) where there is none, or the grid is not one line along the motion
    subroutine trailing_edge_energy(law, g, delta, grid, direction_rad, zone, energy, edges)
        type(contact_law_t), intent(in) :: law
        real(dp), intent(in) :: g(:, :), delta(:, :)
        type(grid_t), intent(in) :: grid
        real(dp), intent(in) :: direction_rad, zone
        real(dp), intent(out) :: energy
        integer, intent(out) :: edges
        real(dp), allocatable :: v(:, :), s(:, :), parts(:, :)
        real(dp) :: totals(2), d(2), zone_cells, w
        integer :: axis, step, n_edges
        energy = ieee_value(1.0_dp, ieee_quiet_nan); edges = 0
        if (.not. edges_measured(grid, direction_rad, axis, step)) return
        d = grid%spacing()
        zone_cells = zone/d(axis)
        w = law%param(ADH_ENERGY)
        v = law%energy(g)
        s = law%attraction(g)
        ! the one line: a row (held by one process of a distributed grid, none on the others) or
        ! a column
        allocate (parts(2, size(g, 3 - axis)))
        if (size(parts, 2) > 0) then
            if (axis == 1) then
                call line_edges(w, zone_cells, g(:, 1), delta(:, 1), v(:, 1), s(:, 1), step, &
                                parts(1, 1), n_edges)
            else
                call line_edges(w, zone_cells, g(1, :), delta(1, :), v(1, :), s(1, :), step, &
                                parts(1, 1), n_edges)
            end if
            parts(2, 1) = real(n_edges, dp)
        end if
        call ordered_sum(grid, parts, totals)
        edges = nint(totals(2))
        if (edges > 0) energy = totals(1)/totals(2)
    end subroutine trailing_edge_energy

    !> Whether the trailing edges of a case on `grid` sliding at `direction_rad` from x are
    !> measured: a line contact along the motion (one row along x, one column along y, the column
    !> not distributed over processes); then the walk's `axis` (1: x, 2: y) and its `step` into an
    !> edge's open side (along -v)
    logical function edges_measured(grid, direction_rad, axis, step) result(yes)
        type(grid_t), intent(in) :: grid
        real(dp), intent(in) :: direction_rad
        integer, intent(out), optional :: axis, step
        real(dp) :: cs, sn
        integer :: axis_, step_
        cs = cos(direction_rad); sn = sin(direction_rad)
        yes = .true.
        if (abs(sn) <= 1.0e-9_dp .and. grid%ny == 1) then
            axis_ = 1; step_ = -nint(sign(1.0_dp, cs))
        else if (abs(cs) <= 1.0e-9_dp .and. grid%nx == 1 .and. .not. grid%is_distributed()) then
            axis_ = 2; step_ = -nint(sign(1.0_dp, sn))
        else
            yes = .false.; axis_ = 0; step_ = 0
        end if
        if (present(axis)) axis = axis_
        if (present(step)) step = step_
    end function edges_measured

    !> The trailing edges of one grid line (periodic): the sum of their energy release rates
    !> `total` [J/m^2] and their number `edges`; `step` (+1 or -1) the walk from an edge into its
    !> open side, `w` the work of adhesion, `zone_cells` the cohesive zone at rest in cells along
    !> the line, `v` and `s` the law's energy and attraction at `g`
    subroutine line_edges(w, zone_cells, g, delta, v, s, step, total, edges)
        real(dp), intent(in) :: w, zone_cells, g(:), delta(:), v(:), s(:)
        integer, intent(in) :: step
        real(dp), intent(out) :: total
        integer, intent(out) :: edges
        real(dp) :: coef(4), gh_a, gh_b, release, ratio
        integer :: n, i, a, b, k, m, run
        logical :: opened
        n = size(g)
        total = 0.0_dp; edges = 0
        do i = 1, n
            ! an edge: a closed cell whose neighbour along -v is open
            if (.not. (g(i) <= 0.0_dp .and. g(wrap(i + step)) > 0.0_dp)) cycle
            ! the contact's length behind it, and the misfit's cubic over up to fit_cells of it
            run = 1
            do while (run < n)
                if (g(wrap(i - run*step)) > 0.0_dp) exit
                run = run + 1
            end do
            if (run < fit_min) cycle
            m = min(run, fit_cells)
            call fit_misfit(i, m, coef)
            release = 0.0_dp; ratio = 1.0_dp
            a = i
            opened = .false.
            do k = 1, n - 1
                b = wrap(i + k*step)
                if (g(b) <= 0.0_dp) exit
                gh_a = g(a) + delta(a) - poly(k - 1)
                gh_b = g(b) + delta(b) - poly(k)
                if (g(b) /= g(a)) then
                    ratio = (gh_b - gh_a)/(g(b) - g(a))
                    release = release + ratio*(v(b) - v(a))
                else
                    release = release + 0.5_dp*(s(a) + s(b))*(gh_b - gh_a)
                end if
                a = b
                if (v(b) >= -spent*w) then
                    release = release - ratio*v(b)
                    opened = .true.; exit
                end if
            end do
            if (.not. opened) cycle
            ! (no release, or a NaN: not an opening crack's; a zone that is not short against the
            ! contact: not a crack's edge)
            if (.not. (release > 0.0_dp)) cycle
            if (run < crack*zone_cells*release/w) cycle
            total = total + release; edges = edges + 1
        end do
    contains
        pure integer function wrap(k) result(kk)
            integer, intent(in) :: k
            kk = modulo(k - 1, n) + 1
        end function wrap

        !> P at `x` cells from the edge along the walk
        pure real(dp) function poly(x) result(y)
            integer, intent(in) :: x
            integer :: e
            real(dp) :: t
            t = real(x, dp)/real(m - 1, dp)
            y = 0.0_dp
            do e = 4, 1, -1
                y = y*t + coef(e)
            end do
        end function poly

        !> The misfit's cubic over the `m` (fit_min to fit_cells) closed cells behind edge `i`, the
        !> j-th at -(j - 1) cells along the walk: its coefficients in t = x/(m - 1)
        subroutine fit_misfit(i, m, coef)
            integer, intent(in) :: i, m
            real(dp), intent(out) :: coef(4)
            real(dp) :: amat(fit_cells, 4), rhs(fit_cells), work(256)
            integer :: j, e, info
            do j = 1, m
                do e = 1, 4
                    amat(j, e) = (-real(j - 1, dp)/real(m - 1, dp))**(e - 1)
                end do
                rhs(j) = delta(wrap(i - (j - 1)*step))
            end do
            call dgels('N', m, 4, 1, amat, fit_cells, rhs, fit_cells, work, size(work), info)
            coef = rhs(1:4)
            ! (not of full rank: cannot happen for distinct points; the edge's own misfit)
            if (info /= 0) coef = [delta(i), 0.0_dp, 0.0_dp, 0.0_dp]
        end subroutine fit_misfit
    end subroutine line_edges

end module veslide_edges
