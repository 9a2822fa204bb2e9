!> Connected patches of a mask on the periodic grid (4-neighbour): their count, mean area and
!> area-weighted gyration (orientation) tensor, and whether some component wraps around the cell
!> along x or y (percolation of the free region, when the mask is p = 0).
!>
!> One algorithm for one process and for a distributed grid. Each process labels the components
!> of its own rows (periodic along x, not along y), each component with its own unwrapped frame
!> (a cell's position is (i - 1 + ox nx, j - 1) cells, ox counting crossings of the x boundary)
!> and its sums (cells, first and second moments). Components that reach neither the first nor
!> the last row are complete: their statistics are final where they were found. The others are
!> joined across the row boundaries between processes (and across the periodic boundary in y)
!> on the first process, by union-find with a translation per join (the frame of one component
!> in that of the other): a component joined to itself with a different translation wraps around
!> the cell, along x or y by the translation's component. Joined sums are shifted into one frame
!> before the tensor is formed, so a patch's tensor does not depend on where it was cut.
!> A component that wraps has no unwrapped shape; its tensor is that of the frame it was
!> assembled in (as in any labelling).
module veslide_patches
    use veslide_kinds, only: dp, i8
    use veslide_grid, only: grid_t
    use veslide_collective, only: gather_to_root, broadcast_from_root, ordered_rank_sum
    use veslide_anisotropy, only: tensor_axes
    implicit none
    private
    public :: patch_stats_t, contact_patches, percolates, label_components, patch_changes
    public :: cell_set_t, cell_set

    type :: patch_stats_t
        integer :: count = 0                    !! number of patches
        real(dp) :: mean_area_fraction = 0.0_dp !! mean patch area / cell area
        real(dp) :: orientation(2, 2) = 0.0_dp  !! area-weighted gyration tensor, trace 1
        real(dp) :: gamma = 0.0_dp              !! its eigenvalue ratio (min/max)
        real(dp) :: theta = 0.0_dp              !! direction of its major axis [rad, 0..pi)
    end type patch_stats_t

    !> A set of cells of the whole grid, as runs of consecutive cells in storage order (x fastest):
    !> a closed set kept compactly (two integers a run) to be compared with later cases
    type :: cell_set_t
        integer(i8), allocatable :: runs(:, :)  !! (first cell, count) a run; cells numbered from 1
    end type cell_set_t

    !> Sums of one component in its frame: cells, x, y, xx, yy, xy (positions in cells)
    integer, parameter :: nsum = 6

contains

    !> Patches of `mask` (the process's rows of `grid` when given, else the whole periodic grid)
    subroutine contact_patches(mask, lx, ly, stats, grid)
        logical, intent(in) :: mask(:, :)
        real(dp), intent(in) :: lx, ly
        type(patch_stats_t), intent(out) :: stats
        type(grid_t), intent(in), optional :: grid
        logical :: wraps(2)
        call label_components(mask, lx, ly, stats, wraps, grid)
    end subroutine contact_patches

    !> Does some connected component of `mask` wrap around the periodic cell along x (dir = 1)
    !> or along y (dir = 2)?
    logical function percolates(mask, dir, grid) result(yes)
        logical, intent(in) :: mask(:, :)
        integer, intent(in) :: dir
        type(grid_t), intent(in), optional :: grid
        type(patch_stats_t) :: stats
        logical :: wraps(2)
        call label_components(mask, 1.0_dp, 1.0_dp, stats, wraps, grid)
        yes = wraps(dir)
    end function percolates

    !> Components of `mask`: their statistics, and whether one wraps along x, y (collective on a
    !> distributed grid; every process returns the same)
    subroutine label_components(mask, lx, ly, stats, wraps, grid)
        logical, intent(in) :: mask(:, :)
        real(dp), intent(in) :: lx, ly
        type(patch_stats_t), intent(out) :: stats
        logical, intent(out) :: wraps(2)
        type(grid_t), intent(in), optional :: grid
        type(grid_t) :: g
        integer, allocatable :: lab(:, :), ox(:, :), btag(:), edges(:, :), all_edges(:, :, :), counts(:)
        real(dp), allocatable :: sums(:, :), bsums(:, :), all_sums(:, :)
        real(dp) :: local(8), joined(8), total(8), d(2), l1, l2
        integer :: nx, nl, nlab, i, k, nb
        logical :: wrap_x, touching

        if (present(grid)) then
            g = grid
        else
            g%nx = size(mask, 1); g%ny = size(mask, 2)
            g%j0 = 0; g%ny_local = size(mask, 2); g%rows_of = [size(mask, 2)]
        end if
        nx = size(mask, 1); nl = size(mask, 2)
        d = [lx/g%nx, ly/g%ny]

        ! 1. the process's rows: labels, frames, sums; wraps along x found inside the rows
        call label_rows(g, mask, lab, ox, sums, nlab, wrap_x)

        ! 2. complete components (touching neither edge row) are final here; the others travel,
        !    with the labels and frames of the two edge rows
        local = 0.0_dp
        local(7) = merge(1.0_dp, 0.0_dp, wrap_x)
        allocate (btag(nlab)); btag = 0; nb = 0
        do k = 1, nlab
            touching = .false.
            if (nl > 0) touching = any(lab(:, 1) == k) .or. any(lab(:, nl) == k)
            if (touching) then
                nb = nb + 1; btag(k) = nb
            else
                call add_patch(d, sums(:, k), local)
            end if
        end do
        allocate (bsums(nsum, nb), edges(nx, 4))
        do k = 1, nlab
            if (btag(k) > 0) bsums(:, btag(k)) = sums(:, k)
        end do
        edges = 0
        if (nl > 0) then
            do i = 1, nx
                if (lab(i, 1) > 0) edges(i, 1) = btag(lab(i, 1))
                if (lab(i, nl) > 0) edges(i, 2) = btag(lab(i, nl))
            end do
            edges(:, 3) = ox(:, 1); edges(:, 4) = ox(:, nl)
        end if
        deallocate (lab, ox, sums)

        ! 3. on the first process: join the travelling components of every process
        call gather_to_root(g, bsums, all_sums, counts)
        call gather_to_root(g, edges, all_edges)
        joined = 0.0_dp
        if (g%is_root()) call join(g, d, all_sums, counts, all_edges, joined)
        call broadcast_from_root(g, joined)

        ! 4. totals: the complete components of every process, in rank order, and the joined ones
        call ordered_rank_sum(g, local, total)
        total = total + joined
        wraps = total(7:8) > 0.0_dp
        stats%count = nint(total(1))
        if (stats%count > 0) then
            stats%mean_area_fraction = total(2)/total(1)/g%cells()
            stats%orientation = reshape([total(3), total(5), total(5), total(4)], [2, 2])/total(6)
            call tensor_axes(stats%orientation, l1, l2, stats%theta)
            stats%gamma = l2/l1
        end if
    end subroutine label_components

    !> Union-find over the travelling components of all processes (rank r's tags are offset
    !> by the counts before it), each union carrying the translation (in cells) of one frame
    !> into the other; then the sums of every joined patch in one frame, and its tensor
    subroutine join(g, d, all_sums, counts, all_edges, acc)
        type(grid_t), intent(in) :: g
        real(dp), intent(in) :: d(2)
        real(dp), intent(in) :: all_sums(:, :)
        integer, intent(in) :: counts(:), all_edges(:, :, :)
        real(dp), intent(inout) :: acc(:)
        integer, allocatable :: parent(:), off(:, :), first(:), root_of(:)
        real(dp), allocatable :: set(:, :)
        integer :: n, r, r2, i, a, b, t(2), ta(2), ra, k, nr, last(2)
        real(dp) :: s(nsum), x, y
        n = size(all_sums, 2); nr = size(counts)
        allocate (parent(n), off(2, n), first(nr))
        parent = [(k, k = 1, n)]; off = 0
        first(1) = 0
        do r = 2, nr
            first(r) = first(r - 1) + counts(r - 1)
        end do
        do r = 1, nr
            if (g%rows_of(r) == 0) cycle
            r2 = r                        ! the next rank holding rows (cyclic)
            do
                r2 = modulo(r2, nr) + 1
                if (g%rows_of(r2) > 0) exit
            end do
            ! rank r's last row touches rank r2's first row; across the top of the cell the
            ! first row sits ny rows above the last
            last(2) = sum(g%rows_of(1:r))
            do i = 1, g%nx
                a = all_edges(i, 2, r); b = all_edges(i, 1, r2)
                if (a == 0 .or. b == 0) cycle
                t(1) = (all_edges(i, 4, r) - all_edges(i, 3, r2))*g%nx
                t(2) = merge(g%ny, 0, last(2) == g%ny)
                call unite(first(r) + a, first(r2) + b, t)
            end do
        end do
        ! each patch's sums shifted into its root's frame, then its tensor
        allocate (set(nsum, n), root_of(n)); set = 0.0_dp
        do k = 1, n
            call find(k, ra, ta)
            root_of(k) = ra
            s = all_sums(:, k); x = ta(1); y = ta(2)
            set(:, ra) = set(:, ra) + [s(1), s(2) + s(1)*x, s(3) + s(1)*y, s(4) + 2.0_dp*x*s(2) + s(1)*x*x, &
                                       s(5) + 2.0_dp*y*s(3) + s(1)*y*y, s(6) + x*s(3) + y*s(2) + s(1)*x*y]
        end do
        do k = 1, n
            if (root_of(k) == k) call add_patch(d, set(:, k), acc)
        end do
    contains
        !> root of k and the translation of k's frame into the root's
        subroutine find(k, root, tr)
            integer, intent(in) :: k
            integer, intent(out) :: root, tr(2)
            root = k; tr = 0
            do while (parent(root) /= root)
                tr = tr + off(:, root); root = parent(root)
            end do
        end subroutine find
        !> join a and b, with pos_in_a = pos_in_b + t; a cycle with a net translation wraps
        subroutine unite(a, b, t)
            integer, intent(in) :: a, b, t(2)
            integer :: ra, rb, ta(2), tb(2), net(2)
            call find(a, ra, ta); call find(b, rb, tb)
            net = t + ta - tb                ! pos_in_ra = pos_in_rb + net
            if (ra == rb) then
                if (net(1) /= 0) acc(7) = 1.0_dp
                if (net(2) /= 0) acc(8) = 1.0_dp
                return
            end if
            parent(rb) = ra; off(:, rb) = net
        end subroutine unite
    end subroutine join

    !> Breadth-first labels of the rows held, periodic along x only
    subroutine label_rows(g, mask, lab, ox, sums, nlab, wrap_x)
        type(grid_t), intent(in) :: g
        logical, intent(in) :: mask(:, :)
        integer, allocatable, intent(out) :: lab(:, :), ox(:, :)
        real(dp), allocatable, intent(out) :: sums(:, :)
        integer, intent(out) :: nlab
        logical, intent(out) :: wrap_x
        integer, allocatable :: qi(:), qj(:)
        real(dp), allocatable :: tmp(:, :)
        integer :: i, j, head, tail, ci, cj, k, ni, nj, dx, nx, nl
        integer, parameter :: di(4) = [1, -1, 0, 0], dj(4) = [0, 0, 1, -1]
        real(dp) :: x, y
        nx = size(mask, 1); nl = size(mask, 2)
        allocate (lab(nx, nl), ox(nx, nl), qi(max(1, nx*nl)), qj(max(1, nx*nl)), sums(nsum, 16))
        lab = 0; ox = 0; nlab = 0; wrap_x = .false.
        do j = 1, nl
            do i = 1, nx
                if (.not. mask(i, j) .or. lab(i, j) /= 0) cycle
                nlab = nlab + 1
                if (nlab > size(sums, 2)) then
                    allocate (tmp(nsum, 2*size(sums, 2))); tmp(:, 1:size(sums, 2)) = sums
                    call move_alloc(tmp, sums)
                end if
                sums(:, nlab) = 0.0_dp
                lab(i, j) = nlab; ox(i, j) = 0
                head = 1; tail = 1; qi(1) = i; qj(1) = j
                do while (head <= tail)
                    ci = qi(head); cj = qj(head); head = head + 1
                    x = real(ci - 1 + ox(ci, cj)*nx, dp); y = real(g%j0 + cj - 1, dp)
                    sums(:, nlab) = sums(:, nlab) + [1.0_dp, x, y, x*x, y*y, x*y]
                    do k = 1, 4
                        ni = ci + di(k); nj = cj + dj(k); dx = ox(ci, cj)
                        if (nj < 1 .or. nj > nl) cycle          ! rows of other processes: joined later
                        if (ni < 1) then
                            ni = nx; dx = dx - 1
                        else if (ni > nx) then
                            ni = 1; dx = dx + 1
                        end if
                        if (.not. mask(ni, nj)) cycle
                        if (lab(ni, nj) /= 0) then
                            if (dx /= ox(ni, nj)) wrap_x = .true.
                            cycle
                        end if
                        lab(ni, nj) = nlab; ox(ni, nj) = dx
                        tail = tail + 1; qi(tail) = ni; qj(tail) = nj
                    end do
                end do
            end do
        end do
    end subroutine label_rows

    !> Add one patch with sums s (positions in cells) to acc = [count, cells, G11, G22, G12, w]
    subroutine add_patch(d, s, acc)
        real(dp), intent(in) :: d(2), s(nsum)
        real(dp), intent(inout) :: acc(:)
        real(dp) :: a, mx, my, gg(3)
        a = s(1)
        mx = s(2)/a; my = s(3)/a
        gg(1) = (s(4)/a - mx*mx + 1.0_dp/12.0_dp)*d(1)**2
        gg(2) = (s(5)/a - my*my + 1.0_dp/12.0_dp)*d(2)**2
        gg(3) = (s(6)/a - mx*my)*d(1)*d(2)
        acc(1) = acc(1) + 1.0_dp
        acc(2) = acc(2) + a
        acc(3:5) = acc(3:5) + a*gg
        acc(6) = acc(6) + a*(gg(1) + gg(2))
    end subroutine add_patch

    !> The patches (4-neighbour components, periodic) of `after` that hold no cell of `before`
    !> (made: their number and cells) and those of `before` that hold no cell of `after` (lost),
    !> on the whole grid held by one process (a study's case).
    !> With `at_before` and `at_after` (either may be absent: no such state), the closed sets of
    !> earlier states at the same control as `before` and as `after`, `bistable` counts the
    !> patches made or lost that one of those states holds the other way: a patch lost is
    !> bistable where a state at `before`'s control held none of its cells, or one at `after`'s
    !> control held one; a patch made, where a state at `before`'s control held one of its cells,
    !> or one at `after`'s control held none.
    subroutine patch_changes(before, after, made, lost, cells_made, cells_lost, at_before, at_after, bistable)
        logical, intent(in) :: before(:, :), after(:, :)
        integer, intent(out) :: made, lost
        integer(i8), intent(out) :: cells_made, cells_lost
        type(cell_set_t), intent(in), optional :: at_before(:), at_after(:)
        integer, intent(out), optional :: bistable
        integer :: nb_made, nb_lost
        ! (an absent set list, here or in apart, holds no earlier state)
        call apart(after, before, made, cells_made, at_before, at_after, nb_made)
        call apart(before, after, lost, cells_lost, at_after, at_before, nb_lost)
        if (present(bistable)) bistable = nb_made + nb_lost
    end subroutine patch_changes

    !> The cells of `mask` (the whole grid) as a set
    function cell_set(mask) result(s)
        logical, intent(in) :: mask(:, :)
        type(cell_set_t) :: s
        integer(i8), allocatable :: runs(:, :), tmp(:, :)
        integer(i8) :: k, first
        integer :: i, j, nrun
        allocate (runs(2, 16)); nrun = 0; first = 0; k = 0
        do j = 1, size(mask, 2)
            do i = 1, size(mask, 1)
                k = k + 1
                if (mask(i, j)) then
                    if (first == 0) first = k
                else if (first > 0) then
                    call add_run(k)
                end if
            end do
        end do
        if (first > 0) call add_run(k + 1)
        s%runs = runs(:, 1:nrun)
    contains
        !> the run from `first` to the cell before `past`
        subroutine add_run(past)
            integer(i8), intent(in) :: past
            nrun = nrun + 1
            if (nrun > size(runs, 2)) then
                allocate (tmp(2, 2*size(runs, 2))); tmp(:, 1:nrun - 1) = runs(:, 1:nrun - 1)
                call move_alloc(tmp, runs)
            end if
            runs(:, nrun) = [first, past - first]; first = 0
        end subroutine add_run
    end function cell_set

    !> The components of `mask` with no cell in `other`: their number and cells (the rows'
    !> labelling, periodic along x, with the labels of the last and first rows joined: periodic
    !> along y on the whole grid); with `held` and `unheld`, `nb` counts those of them that hold a
    !> cell of one of the sets `held`, or no cell of one of the sets `unheld`
    subroutine apart(mask, other, n, cells, held, unheld, nb)
        logical, intent(in) :: mask(:, :), other(:, :)
        integer, intent(out) :: n
        integer(i8), intent(out) :: cells
        type(cell_set_t), intent(in), optional :: held(:), unheld(:)
        integer, intent(out), optional :: nb
        type(grid_t) :: g
        integer, allocatable :: lab(:, :), ox(:, :), up(:)
        real(dp), allocatable :: sums(:, :), size_of(:)
        logical, allocatable :: touches(:), flagged(:), hits(:)
        integer :: nlab, nx, ny, i, j, k, e
        logical :: wrap_x
        nx = size(mask, 1); ny = size(mask, 2)
        g%nx = nx; g%ny = ny; g%j0 = 0; g%ny_local = ny; g%rows_of = [ny]
        call label_rows(g, mask, lab, ox, sums, nlab, wrap_x)
        up = [(k, k = 1, nlab)]
        do i = 1, nx
            if (lab(i, 1) > 0 .and. lab(i, ny) > 0) up(top(lab(i, 1))) = top(lab(i, ny))
        end do
        allocate (touches(nlab), size_of(nlab), flagged(nlab), hits(nlab))
        touches = .false.; size_of = 0.0_dp; flagged = .false.
        do k = 1, nlab
            size_of(top(k)) = size_of(top(k)) + sums(1, k)
        end do
        do j = 1, ny
            do i = 1, nx
                if (lab(i, j) > 0 .and. other(i, j)) touches(top(lab(i, j))) = .true.
            end do
        end do
        if (present(held)) then
            do e = 1, size(held)
                call hit(held(e)); flagged = flagged .or. hits
            end do
        end if
        if (present(unheld)) then
            do e = 1, size(unheld)
                call hit(unheld(e)); flagged = flagged .or. .not. hits
            end do
        end if
        n = 0; cells = 0_i8
        if (present(nb)) nb = 0
        do k = 1, nlab
            if (up(k) /= k .or. touches(k)) cycle
            n = n + 1; cells = cells + nint(size_of(k), i8)
            if (present(nb) .and. flagged(k)) nb = nb + 1
        end do
    contains
        integer function top(k0) result(k)
            integer, intent(in) :: k0
            k = k0
            do while (up(k) /= k)
                k = up(k)
            end do
        end function top

        !> hits(k): component k (a root) holds a cell of the set s
        subroutine hit(s)
            type(cell_set_t), intent(in) :: s
            integer(i8) :: r, c
            integer :: l
            hits = .false.
            do r = 1, size(s%runs, 2, i8)
                do c = s%runs(1, r), s%runs(1, r) + s%runs(2, r) - 1
                    l = lab(int(modulo(c - 1, int(nx, i8)) + 1), int((c - 1)/nx + 1))
                    if (l > 0) hits(top(l)) = .true.
                end do
            end do
        end subroutine hit
    end subroutine apart

end module veslide_patches
