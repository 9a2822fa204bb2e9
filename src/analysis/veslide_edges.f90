!> The edges of a sliding adhesive contact: the energy release rate of each edge, where the gap
!> opens as the solid leaves the contact (trailing) and where it closes as the solid enters it
!> (leading) (docs/adhesion.md, *Contact edges*).
!>
!> Relative to the rigid surface the solid's material moves along -v: it enters a contact at the
!> contact's leading edge (its +v side) and leaves it at the trailing edge (its -v side). Each edge
!> is a crack that runs at the speed v: an opening one at the trailing edge, a closing one at the
!> leading edge. The energy release rate of such a crack as its far field sees it is
!> G = K^2/(2 E0*), E0 the relaxed modulus: w at rest; in motion the trailing edge's rises toward
!> (Einf/E0) w (Persson and Brener, PRE 71 (2005) 036123; with a cohesive zone, Schapery's and
!> Greenwood's steady-crack analyses), and the leading edge's falls below w, its tip glassy and its
!> far field relaxed. It is measured here without K, as the J integral of the relaxed solid along
!> the line through the edge:
!>   G = integral of sigma d(g + Delta - P)
!> from L closed cells behind the edge, through it, and out over its open cells until the law's
!> energy V(g) has risen to -1e-3 w (the rest of the attraction, -V, added at the last step's
!> d ghat/d g; a walk that meets the next closed cell first is not measured). sigma is the
!> attraction, -p: on the contact side the traction itself (trapezoids), on the open side the
!> law's (exact steps below). Delta = u0 - u is the relaxed solid's misfit: u0 the displacement
!> the solid at rest (the kernel at zero speed) would have under the case's traction, u the
!> solid's own. P is the quartic fitted (least squares) to Delta over the closed cells L to
!> L + W - 1 behind the edge (W = max(fit_width, L)), where the misfit is smooth: it continues the
!> smooth misfit across the edge, so that g + Delta - P is the relaxed solid's opening. The step
!> from the last closed cell to the first open one takes the edge cell's repulsive traction
!> p + sigma against the misfit's change over the trapezoid's half of the step: at a closing edge
!> the contact's reaction gathers in its last cells, and without this term the leading edge of
!> Johnson's sliding wave read 0.060 to 0.331 w on 2048 to 32768 cells, with it 0.331 to 0.344 w.
!> Between neighbouring open cells the integral is (d ghat/d g) (V(g_b) - V(g_a)), exact where
!> ghat is linear in g: an elastic solid (Delta = 0) gives exactly w at every edge.
!>
!> The lead-in L. At an opening edge the misfit is smooth up to the edge, the material there
!> having been in contact a while; at a closing edge the material has just come in, and its misfit
!> carries the edge's imprint over about v tau into the contact, which the contact side's part
!> of the integral takes in once L is past it (the J integral of the relaxed solid over a path
!> that encloses it). L doubles from lead_in (16 cells) until G at L agrees with G at L/2 to
!> `plateau` (1e-2) of it, the fit window staying within the half of the contact behind the edge:
!> else the edge is not measured. On Johnson's sliding wave the leading edge is taken at L of 2 to
!> 3 v tau (128 and 256 cells where v tau is 41 and 123), at the first doubling where v tau is a
!> few cells, and where v tau is a fair part of the contact no plateau is found.
!>
!> An edge is measured when, besides, the contact behind it is at least `crack` (4) times the
!> cohesive zone its G makes (a0 G/w, a0 = pi E0* w/(4 sigma0^2) the zone at rest: the zone grows
!> with K^2), its attraction is spent before the next closed cell, its release is positive, and
!> the misfit is smooth over the fit window where G settled (the polynomial's rms residual at most
!> `smooth_fit` of the law's length): else it is not a crack's edge (a long range's zone as wide
!> as the contact read 10.37 w against Einf/E0 = 10 glassy), or it has no smooth far field (a
!> rough surface in contact: its relaxed misfit is as rough as the surface).
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
    use veslide_contact_law, only: contact_law_t, ADH_ENERGY, ADH_RANGE
    use veslide_collective, only: ordered_sum
    use veslide_lapack, only: dgels
    implicit none
    private
    public :: edge_energies, edges_measured

    !> the first lead-in into the contact [cells], and the fit window's least width [cells]
    integer, parameter :: lead_in = 16, fit_width = 64
    !> the misfit's polynomial: its degree (a quartic: a cubic over 64 cells took the glassy limit
    !> to 10.012 w against Einf/E0 = 10, the quartic to 9.9999 w, 9.998 w with the step across
    !> the edge)
    integer, parameter :: degree = 4
    !> G is taken where it changes by at most this fraction of it as the lead-in doubles
    real(dp), parameter :: plateau = 1.0e-2_dp
    !> the misfit is smooth over the fit window where the polynomial's rms residual there is at most
    !> this fraction of the law's length (rho, or Dugdale's opening w/sigma0): an error of that
    !> size in the opening moves G by about as much of w. Johnson's waves left at most 7e-4 of it
    !> where G settled, rough profiles 2e-2 to 1e-1 (whose G read 17.6 to 890 w, Einf/E0 = 11)
    real(dp), parameter :: smooth_fit = 5.0e-3_dp
    !> the walk stops where the law's energy has risen above -spent w (the rest, -V(g_end), added at
    !> the last step's d ghat/d g); an edge whose walk meets a closed cell first is not measured
    real(dp), parameter :: spent = 1.0e-3_dp
    !> an edge is measured when the contact behind it is at least `crack` times the cohesive zone
    !> its G makes (a0 G/w, a0 the zone at rest)
    real(dp), parameter :: crack = 4.0_dp

contains

    !> The mean energy release rates [J/m^2] over the trailing edges (`trailing`) and the leading
    !> edges (`leading`) of the closed cells of the gap `g` [m] under the traction `p` [Pa] (an
    !> adhesive law's), and the numbers of edges measured (`n_trailing`, `n_leading`), for a
    !> motion at `direction_rad` from x; `delta` [m] is the relaxed solid's misfit u0 - u (zero for
    !> an elastic solid or at rest), `zone` [m] the law's cohesive zone at rest,
    !> pi E0* w/(4 sigma0^2). NaN (and no edge) where there is none, or the grid is not one line
    !> along the motion
    subroutine edge_energies(law, g, p, delta, grid, direction_rad, zone, trailing, n_trailing, leading, &
                             n_leading)
        type(contact_law_t), intent(in) :: law
        real(dp), intent(in) :: g(:, :), p(:, :), delta(:, :)
        type(grid_t), intent(in) :: grid
        real(dp), intent(in) :: direction_rad, zone
        real(dp), intent(out) :: trailing, leading
        integer, intent(out) :: n_trailing, n_leading
        real(dp), allocatable :: v(:, :), s(:, :), parts(:, :)
        real(dp) :: totals(4), d(2), zone_cells, w, length
        integer :: axis, step, side, n_edges
        trailing = ieee_value(1.0_dp, ieee_quiet_nan); leading = trailing
        n_trailing = 0; n_leading = 0
        if (.not. edges_measured(grid, direction_rad, axis, step)) return
        d = grid%spacing()
        zone_cells = zone/d(axis)
        w = law%param(ADH_ENERGY)
        length = law%param(ADH_RANGE)
        v = law%energy(g)
        s = law%attraction(g)
        ! the one line: a row (held by one process of a distributed grid, none on the others) or
        ! a column; the trailing edges open along -v (step), the leading ones along +v (-step)
        allocate (parts(4, size(g, 3 - axis)))
        if (size(parts, 2) > 0) then
            do side = 0, 1
                if (axis == 1) then
                    call line_edges(w, length, zone_cells, g(:, 1), p(:, 1), delta(:, 1), v(:, 1), s(:, 1), &
                                    (1 - 2*side)*step, parts(1 + 2*side, 1), n_edges)
                else
                    call line_edges(w, length, zone_cells, g(1, :), p(1, :), delta(1, :), v(1, :), s(1, :), &
                                    (1 - 2*side)*step, parts(1 + 2*side, 1), n_edges)
                end if
                parts(2 + 2*side, 1) = real(n_edges, dp)
            end do
        end if
        call ordered_sum(grid, parts, totals)
        n_trailing = nint(totals(2)); n_leading = nint(totals(4))
        if (n_trailing > 0) trailing = totals(1)/totals(2)
        if (n_leading > 0) leading = totals(3)/totals(4)
    end subroutine edge_energies

    !> Whether the edges of a case on `grid` sliding at `direction_rad` from x are measured: a
    !> line contact along the motion (one row along x, one column along y, the column not
    !> distributed over processes); then the walk's `axis` (1: x, 2: y) and its `step` into a
    !> trailing edge's open side (along -v)
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

    !> The edges of one grid line (periodic) that open along `step` (+1 or -1: the walk from an
    !> edge into its open side): the sum of their energy release rates `total` [J/m^2] and their
    !> number `edges`; `w` the work of adhesion, `length` the law's length (rho, or w/sigma0),
    !> `zone_cells` the cohesive zone at rest in cells along the line, `p` the traction, `v` and
    !> `s` the law's energy and attraction at `g`
    subroutine line_edges(w, length, zone_cells, g, p, delta, v, s, step, total, edges)
        real(dp), intent(in) :: w, length, zone_cells, g(:), p(:), delta(:), v(:), s(:)
        integer, intent(in) :: step
        real(dp), intent(out) :: total
        integer, intent(out) :: edges
        real(dp) :: release, before, residual
        integer :: n, i, run, lead
        logical :: opened, settled
        n = size(g)
        total = 0.0_dp; edges = 0
        do i = 1, n
            ! an edge: a closed cell whose neighbour along the step is open
            if (.not. (g(i) <= 0.0_dp .and. g(wrap(i + step)) > 0.0_dp)) cycle
            ! the contact's length behind it
            run = 1
            do while (run < n)
                if (g(wrap(i - run*step)) > 0.0_dp) exit
                run = run + 1
            end do
            ! the lead-in doubles until G settles, the fit window within the contact's half
            lead = lead_in; settled = .false.
            before = 0.0_dp
            do while (2*(lead + max(fit_width, lead)) <= run)
                call edge_release(i, lead, max(fit_width, lead), release, residual, opened)
                if (.not. opened) exit
                if (lead > lead_in) then
                    if (abs(release - before) <= plateau*abs(release)) then
                        settled = .true.; exit
                    end if
                end if
                before = release; lead = 2*lead
            end do
            if (.not. settled) cycle
            ! (a misfit that no polynomial follows, as a rough surface's in contact: no far field)
            if (residual > smooth_fit*length) cycle
            ! (no release, or a NaN: not a crack's; a zone that is not short against the contact:
            ! not a crack's edge)
            if (.not. (release > 0.0_dp)) cycle
            if (run < crack*zone_cells*release/w) cycle
            total = total + release; edges = edges + 1
        end do
    contains
        pure integer function wrap(k) result(kk)
            integer, intent(in) :: k
            kk = modulo(k - 1, n) + 1
        end function wrap

        !> The J integral through edge `i` from `lead` closed cells behind it, the misfit's
        !> polynomial fitted over the `width` closed cells beyond those (`residual` its rms
        !> residual [m]); `opened` false where the walk meets a closed cell before the attraction
        !> is spent
        subroutine edge_release(i, lead, width, release, residual, opened)
            integer, intent(in) :: i, lead, width
            real(dp), intent(out) :: release, residual
            logical, intent(out) :: opened
            real(dp) :: coef(degree + 1), scale, gh_a, gh_b, ratio
            integer :: k, a, b
            scale = real(lead + width - 1, dp)
            call fit_misfit(i, lead, width, scale, coef, residual)
            release = 0.0_dp; opened = .false.
            ! the contact side: the traction's trapezoids
            a = wrap(i - lead*step)
            gh_a = g(a) + delta(a) - poly(coef, scale, -lead)
            do k = -lead + 1, 0
                b = wrap(i + k*step)
                gh_b = g(b) + delta(b) - poly(coef, scale, k)
                release = release - 0.5_dp*(p(a) + p(b))*(gh_b - gh_a)
                a = b; gh_a = gh_b
            end do
            ! the step across the edge: the edge cell's repulsive traction p + sigma against the
            ! misfit's change over the half of the step that lies in the contact (the trapezoid's
            ! half; the opening's own change is the attraction's, below)
            b = wrap(i + step)
            release = release - 0.5_dp*(p(i) + s(i))*((delta(b) - poly(coef, scale, 1)) - &
                                                       (delta(i) - poly(coef, scale, 0)))
            ! the open side: the law's steps
            ratio = 1.0_dp
            do k = 1, n - 1
                b = wrap(i + k*step)
                if (g(b) <= 0.0_dp) exit
                gh_b = g(b) + delta(b) - poly(coef, scale, k)
                if (g(b) /= g(a)) then
                    ratio = (gh_b - gh_a)/(g(b) - g(a))
                    release = release + ratio*(v(b) - v(a))
                else
                    release = release + 0.5_dp*(s(a) + s(b))*(gh_b - gh_a)
                end if
                a = b; gh_a = gh_b
                if (v(b) >= -spent*w) then
                    release = release - ratio*v(b)
                    opened = .true.; exit
                end if
            end do
        end subroutine edge_release

        !> The misfit's polynomial of coefficients `coef` in t = x/`scale` at `x` cells from the edge
        !> along the walk
        pure real(dp) function poly(coef, scale, x) result(y)
            real(dp), intent(in) :: coef(degree + 1), scale
            integer, intent(in) :: x
            integer :: e
            real(dp) :: t
            t = real(x, dp)/scale
            y = 0.0_dp
            do e = degree + 1, 1, -1
                y = y*t + coef(e)
            end do
        end function poly

        !> The misfit's polynomial over the `width` closed cells `lead` to `lead + width - 1`
        !> behind edge `i`, the j-th at -j cells along the walk: its coefficients in t = x/scale,
        !> and the rms of its residuals [m]
        subroutine fit_misfit(i, lead, width, scale, coef, residual)
            integer, intent(in) :: i, lead, width
            real(dp), intent(in) :: scale
            real(dp), intent(out) :: coef(degree + 1), residual
            real(dp), allocatable :: amat(:, :), rhs(:), work(:)
            integer :: j, e, info
            allocate (amat(width, degree + 1), rhs(width), work(64*(degree + 1) + width))
            do j = 1, width
                do e = 1, degree + 1
                    amat(j, e) = (-real(lead + j - 1, dp)/scale)**(e - 1)
                end do
                rhs(j) = delta(wrap(i - (lead + j - 1)*step))
            end do
            call dgels('N', width, degree + 1, 1, amat, width, rhs, width, work, size(work), info)
            coef = rhs(1:degree + 1)
            ! (dgels leaves the residuals' components beyond the coefficients)
            residual = sqrt(sum(rhs(degree + 2:)**2)/width)
            ! (not of full rank: cannot happen for distinct points; no fit, no measure)
            if (info /= 0) then
                coef = [delta(wrap(i - lead*step)), (0.0_dp, e=1, degree)]
                residual = huge(1.0_dp)
            end if
        end subroutine fit_misfit
    end subroutine line_edges

end module veslide_edges
