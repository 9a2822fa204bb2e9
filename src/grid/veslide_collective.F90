!> Operations over a grid shared by several processes: sums in a fixed order, extrema, counts,
!> halo rows, and one verdict on an error. On a grid that is not distributed they are the serial
!> operations; built with -DVESLIDE_MPI (the MPI build, mpi/) they use MPI's collectives.
!>
!> Sums are deterministic: the caller supplies one partial sum per storage column (a row j of a
!> real field, or a column b of the half-spectrum's storage), each computed sequentially by one
!> thread, and `ordered_sum` adds the columns in their global order. The result is the same
!> whatever the number of threads, and, for the same partial sums, whatever the number of
!> processes (the columns are gathered, not reduced in a tree).
module veslide_collective
    use veslide_kinds, only: dp, i8
    use veslide_error, only: error_t, fatal_error
    use veslide_grid, only: grid_t
    use veslide_clock, only: wall_seconds
#ifdef VESLIDE_MPI
    use mpi_f08
#endif
    implicit none
    private
    public :: ordered_sum, ordered_sum_scalar, global_min, global_max, global_count, global_any, halo_rows, share_error
    public :: mpi_enabled, gather_all, gather_to_root, broadcast_from_root, ordered_rank_sum, collective_seconds

    !> Wall time this process has spent in the collectives of the solver's loop (ordered sums,
    !> extrema, counts) so far [s]: what a distributed grid costs beyond the transforms
    real(dp), save :: collective_seconds = 0.0_dp

    !> Was the library built with MPI (-DVESLIDE_MPI)?
#ifdef VESLIDE_MPI
    logical, parameter :: mpi_enabled = .true.
#else
    logical, parameter :: mpi_enabled = .false.
#endif

    interface global_min
        module procedure global_min_scalar, global_min_array
    end interface global_min

    interface global_max
        module procedure global_max_scalar, global_max_array
    end interface global_max

    interface global_count
        module procedure global_count_i4, global_count_i8
    end interface global_count

    interface gather_to_root
        module procedure gather_columns_r, gather_blocks_i
    end interface gather_to_root

contains

    !> totals(k) = sum over the global columns c, in order, of parts(k, c): parts holds this
    !> process's columns (rows of a real field, or, with `spectral`, the columns of the
    !> half-spectrum's storage)
    subroutine ordered_sum(grid, parts, totals, spectral)
        type(grid_t), intent(in) :: grid
        real(dp), intent(in) :: parts(:, :)
        real(dp), intent(out) :: totals(:)
        logical, intent(in), optional :: spectral
        integer :: c
#ifdef VESLIDE_MPI
        real(dp), allocatable :: all(:, :), mine(:, :)
        integer, allocatable :: counts(:), displs(:)
        integer :: r, k
        type(MPI_Comm) :: comm
        logical :: spectral_
        real(dp) :: t0
        if (grid%is_distributed()) then
            spectral_ = .false.; if (present(spectral)) spectral_ = spectral
            k = size(parts, 1)
            if (spectral_) then
                counts = k*grid%spectral_of
            else
                counts = k*grid%rows_of
            end if
            allocate (displs(grid%ranks))
            displs(1) = 0
            do r = 2, grid%ranks
                displs(r) = displs(r - 1) + counts(r - 1)
            end do
            allocate (all(k, sum(counts)/max(k, 1)))
            comm%MPI_VAL = grid%comm
            mine = parts                       ! contiguous (parts may be an array section)
            t0 = wall_seconds()
            call MPI_Allgatherv(mine, size(mine), MPI_DOUBLE_PRECISION, all, counts, displs, &
                                MPI_DOUBLE_PRECISION, comm)
            collective_seconds = collective_seconds + (wall_seconds() - t0)
            totals = 0.0_dp
            do c = 1, size(all, 2)
                totals = totals + all(:, c)
            end do
            return
        end if
#endif
        totals = 0.0_dp
        do c = 1, size(parts, 2)
            totals = totals + parts(:, c)
        end do
    end subroutine ordered_sum

    !> The ordered sum of one quantity: parts(c) per column
    function ordered_sum_scalar(grid, parts, spectral) result(total)
        type(grid_t), intent(in) :: grid
        real(dp), intent(in) :: parts(:)
        logical, intent(in), optional :: spectral
        real(dp) :: total
        real(dp) :: t(1)
        call ordered_sum(grid, reshape(parts, [1, size(parts)]), t, spectral)
        total = t(1)
    end function ordered_sum_scalar

    !> x <- min of x over the processes
    subroutine global_min_scalar(grid, x)
        type(grid_t), intent(in) :: grid
        real(dp), intent(inout) :: x
        real(dp) :: a(1)
        a(1) = x
        call extremum(grid, a, .false.)
        x = a(1)
    end subroutine global_min_scalar

    subroutine global_min_array(grid, x)
        type(grid_t), intent(in) :: grid
        real(dp), intent(inout) :: x(:)
        call extremum(grid, x, .false.)
    end subroutine global_min_array

    !> x <- max of x over the processes
    subroutine global_max_scalar(grid, x)
        type(grid_t), intent(in) :: grid
        real(dp), intent(inout) :: x
        real(dp) :: a(1)
        a(1) = x
        call extremum(grid, a, .true.)
        x = a(1)
    end subroutine global_max_scalar

    subroutine global_max_array(grid, x)
        type(grid_t), intent(in) :: grid
        real(dp), intent(inout) :: x(:)
        call extremum(grid, x, .true.)
    end subroutine global_max_array

    !> x <- the largest (`largest`) or smallest x over the processes, element by element (exact)
    subroutine extremum(grid, x, largest)
        type(grid_t), intent(in) :: grid
        real(dp), intent(inout) :: x(:)
        logical, intent(in) :: largest
#ifdef VESLIDE_MPI
        type(MPI_Comm) :: comm
        real(dp) :: t0
        if (grid%is_distributed()) then
            comm%MPI_VAL = grid%comm
            t0 = wall_seconds()
            if (largest) then
                call MPI_Allreduce(MPI_IN_PLACE, x, size(x), MPI_DOUBLE_PRECISION, MPI_MAX, comm)
            else
                call MPI_Allreduce(MPI_IN_PLACE, x, size(x), MPI_DOUBLE_PRECISION, MPI_MIN, comm)
            end if
            collective_seconds = collective_seconds + (wall_seconds() - t0)
        end if
#endif
    end subroutine extremum

    !> n <- sum of n over the processes (exact)
    subroutine global_count_i8(grid, n)
        type(grid_t), intent(in) :: grid
        integer(i8), intent(inout) :: n(:)
#ifdef VESLIDE_MPI
        type(MPI_Comm) :: comm
        real(dp) :: t0
        if (grid%is_distributed()) then
            comm%MPI_VAL = grid%comm
            t0 = wall_seconds()
            call MPI_Allreduce(MPI_IN_PLACE, n, size(n), MPI_INTEGER8, MPI_SUM, comm)
            collective_seconds = collective_seconds + (wall_seconds() - t0)
        end if
#endif
    end subroutine global_count_i8

    subroutine global_count_i4(grid, n)
        type(grid_t), intent(in) :: grid
        integer, intent(inout) :: n
        integer(i8) :: a(1)
        a(1) = n
        call global_count_i8(grid, a)
        n = int(a(1))
    end subroutine global_count_i4

    !> yes <- any process's yes
    subroutine global_any(grid, yes)
        type(grid_t), intent(in) :: grid
        logical, intent(inout) :: yes
        integer(i8) :: a(1)
        a(1) = merge(1_i8, 0_i8, yes)
        call global_count_i8(grid, a)
        yes = a(1) > 0
    end subroutine global_any

    !> ext(:, 1-depth : ny_local+depth): the process's rows of f with `depth` rows of the periodic
    !> neighbours on either side (from other processes where the grid is distributed)
    subroutine halo_rows(grid, f, depth, ext)
        type(grid_t), intent(in) :: grid
        real(dp), intent(in) :: f(:, :)
        integer, intent(in) :: depth
        real(dp), allocatable, intent(out) :: ext(:, :)
        integer :: d, nl
        nl = size(f, 2)
        allocate (ext(size(f, 1), 1 - depth:nl + depth))
        ext(:, 1:nl) = f
#ifdef VESLIDE_MPI
        if (grid%is_distributed()) then
            call exchange()
            return
        end if
#endif
        do d = 1, depth
            ext(:, 1 - d) = f(:, modulo(-d, nl) + 1)
            ext(:, nl + d) = f(:, modulo(d - 1, nl) + 1)
        end do
#ifdef VESLIDE_MPI
    contains
        !> Every process knows every share, so each works out which of its rows the others need
        !> (all-to-all, any depth and any slab thickness, one's own rows included)
        subroutine exchange()
            integer, allocatable :: first(:), scount(:), rcount(:), sdispl(:), rdispl(:)
            real(dp), allocatable :: sbuf(:, :), rbuf(:, :)
            integer :: r, k, jg, pos, nx
            type(MPI_Comm) :: comm
            nx = size(f, 1)
            allocate (first(0:grid%ranks - 1), scount(grid%ranks), rcount(grid%ranks), sdispl(grid%ranks), &
                      rdispl(grid%ranks))
            first(0) = 0
            do r = 1, grid%ranks - 1
                first(r) = first(r - 1) + grid%rows_of(r)
            end do
            ! what this process sends: for every rank r, its halo rows that this process owns
            scount = 0
            do r = 0, grid%ranks - 1
                do k = 1, 2*depth
                    jg = halo_row(first(r), grid%rows_of(r + 1), k)
                    if (jg > grid%j0 .and. jg <= grid%j0 + nl) scount(r + 1) = scount(r + 1) + 1
                end do
            end do
            allocate (sbuf(nx, max(1, sum(scount))))
            pos = 0
            do r = 0, grid%ranks - 1
                do k = 1, 2*depth
                    jg = halo_row(first(r), grid%rows_of(r + 1), k)
                    if (jg > grid%j0 .and. jg <= grid%j0 + nl) then
                        pos = pos + 1; sbuf(:, pos) = f(:, jg - grid%j0)
                    end if
                end do
            end do
            ! what it receives: its own 2 depth halo rows, grouped by owner in owner order
            rcount = 0
            do k = 1, 2*depth
                jg = halo_row(grid%j0, nl, k)
                r = owner(jg)
                rcount(r + 1) = rcount(r + 1) + 1
            end do
            sdispl(1) = 0; rdispl(1) = 0
            do r = 2, grid%ranks
                sdispl(r) = sdispl(r - 1) + scount(r - 1)*nx
                rdispl(r) = rdispl(r - 1) + rcount(r - 1)*nx
            end do
            allocate (rbuf(nx, 2*depth))
            comm%MPI_VAL = grid%comm
            call MPI_Alltoallv(sbuf, scount*nx, sdispl, MPI_DOUBLE_PRECISION, rbuf, rcount*nx, rdispl, &
                               MPI_DOUBLE_PRECISION, comm)
            ! unpack in the order the owners packed: by owner, then by k
            pos = 0
            do r = 0, grid%ranks - 1
                do k = 1, 2*depth
                    jg = halo_row(grid%j0, nl, k)
                    if (owner(jg) /= r) cycle
                    pos = pos + 1
                    if (k <= depth) then
                        ext(:, 1 - k) = rbuf(:, pos)
                    else
                        ext(:, nl + k - depth) = rbuf(:, pos)
                    end if
                end do
            end do
        end subroutine exchange

        !> Global row (1-based) of halo row k of the share starting after row `start` with `n` rows:
        !> k = 1..depth below (start, start-1, ...), depth+1..2 depth above
        pure integer function halo_row(start, n, k) result(jg)
            integer, intent(in) :: start, n, k
            if (k <= depth) then
                jg = modulo(start - k, grid%ny) + 1
            else
                jg = modulo(start + n + (k - depth) - 1, grid%ny) + 1
            end if
        end function halo_row

        pure integer function owner(jg) result(r)
            integer, intent(in) :: jg
            integer :: s
            s = 0
            do r = 0, grid%ranks - 1
                if (jg > s .and. jg <= s + grid%rows_of(r + 1)) return
                s = s + grid%rows_of(r + 1)
            end do
            r = grid%ranks - 1
        end function owner

#endif
    end subroutine halo_rows

    !> On every process: the columns of `a` of every process, in rank order (a few values each:
    !> points a solver must see whoever holds them)
    subroutine gather_all(grid, a, all)
        type(grid_t), intent(in) :: grid
        real(dp), intent(in) :: a(:, :)
        real(dp), allocatable, intent(out) :: all(:, :)
#ifdef VESLIDE_MPI
        integer, allocatable :: counts(:), displs(:)
        real(dp), allocatable :: mine(:, :)
        integer :: r, n
        type(MPI_Comm) :: comm
        real(dp) :: t0
        if (grid%is_distributed()) then
            comm%MPI_VAL = grid%comm
            t0 = wall_seconds()
            allocate (counts(grid%ranks), displs(grid%ranks))
            n = size(a, 2)*size(a, 1)
            call MPI_Allgather(n, 1, MPI_INTEGER, counts, 1, MPI_INTEGER, comm)
            displs(1) = 0
            do r = 2, grid%ranks
                displs(r) = displs(r - 1) + counts(r - 1)
            end do
            allocate (all(size(a, 1), sum(counts)/max(1, size(a, 1))))
            mine = a
            call MPI_Allgatherv(mine, size(mine), MPI_DOUBLE_PRECISION, all, counts, displs, &
                                MPI_DOUBLE_PRECISION, comm)
            collective_seconds = collective_seconds + (wall_seconds() - t0)
            return
        end if
#endif
        all = a
    end subroutine gather_all

    !> On the first process: the columns of `a` of every process, in rank order, and how many
    !> each gave (elsewhere `all` is empty)
    subroutine gather_columns_r(grid, a, all, counts)
        type(grid_t), intent(in) :: grid
        real(dp), intent(in) :: a(:, :)
        real(dp), allocatable, intent(out) :: all(:, :)
        integer, allocatable, intent(out) :: counts(:)
#ifdef VESLIDE_MPI
        integer, allocatable :: displs(:)
        real(dp), allocatable :: mine(:, :)
        integer :: r, n
        type(MPI_Comm) :: comm
        if (grid%is_distributed()) then
            comm%MPI_VAL = grid%comm
            allocate (counts(grid%ranks), displs(grid%ranks))
            n = size(a, 2)
            call MPI_Gather(n, 1, MPI_INTEGER, counts, 1, MPI_INTEGER, 0, comm)
            if (grid%is_root()) then
                allocate (all(size(a, 1), sum(counts)))
            else
                allocate (all(size(a, 1), 0))
            end if
            displs(1) = 0
            do r = 2, grid%ranks
                displs(r) = displs(r - 1) + counts(r - 1)*size(a, 1)
            end do
            mine = a
            call MPI_Gatherv(mine, size(mine), MPI_DOUBLE_PRECISION, all, counts*size(a, 1), displs, &
                             MPI_DOUBLE_PRECISION, 0, comm)
            return
        end if
#endif
        all = a
        counts = [size(a, 2)]
    end subroutine gather_columns_r

    !> On the first process: the block `a` (the same shape everywhere) of every process,
    !> all(:, :, r) for rank r - 1 (elsewhere `all` is empty)
    subroutine gather_blocks_i(grid, a, all)
        type(grid_t), intent(in) :: grid
        integer, intent(in) :: a(:, :)
        integer, allocatable, intent(out) :: all(:, :, :)
#ifdef VESLIDE_MPI
        integer, allocatable :: mine(:, :)
        type(MPI_Comm) :: comm
        if (grid%is_distributed()) then
            comm%MPI_VAL = grid%comm
            if (grid%is_root()) then
                allocate (all(size(a, 1), size(a, 2), grid%ranks))
            else
                allocate (all(size(a, 1), size(a, 2), 1))
            end if
            mine = a
            call MPI_Gather(mine, size(mine), MPI_INTEGER, all, size(mine), MPI_INTEGER, 0, comm)
            return
        end if
#endif
        allocate (all(size(a, 1), size(a, 2), 1))
        all(:, :, 1) = a
    end subroutine gather_blocks_i

    !> x <- the first process's x
    subroutine broadcast_from_root(grid, x)
        type(grid_t), intent(in) :: grid
        real(dp), intent(inout) :: x(:)
#ifdef VESLIDE_MPI
        type(MPI_Comm) :: comm
        if (grid%is_distributed()) then
            comm%MPI_VAL = grid%comm
            call MPI_Bcast(x, size(x), MPI_DOUBLE_PRECISION, 0, comm)
        end if
#endif
    end subroutine broadcast_from_root

    !> total = the sum of every process's `local`, added in rank order (deterministic)
    subroutine ordered_rank_sum(grid, local, total)
        type(grid_t), intent(in) :: grid
        real(dp), intent(in) :: local(:)
        real(dp), intent(out) :: total(:)
#ifdef VESLIDE_MPI
        real(dp), allocatable :: all(:, :), mine(:)
        integer :: r
        type(MPI_Comm) :: comm
        if (grid%is_distributed()) then
            comm%MPI_VAL = grid%comm
            allocate (all(size(local), grid%ranks))
            mine = local
            call MPI_Allgather(mine, size(mine), MPI_DOUBLE_PRECISION, all, size(mine), MPI_DOUBLE_PRECISION, comm)
            total = 0.0_dp
            do r = 1, grid%ranks
                total = total + all(:, r)
            end do
            return
        end if
#endif
        total = local
    end subroutine ordered_rank_sum

    !> One verdict for all processes: when any has an error, every one returns an error (the
    !> message of the lowest rank that failed); a no-op on a grid that is not distributed
    subroutine share_error(grid, error)
        type(grid_t), intent(in) :: grid
        type(error_t), allocatable, intent(inout) :: error
#ifdef VESLIDE_MPI
        integer :: failed, first, n(2)
        character(len=:), allocatable :: msg
        type(MPI_Comm) :: comm
        if (.not. grid%is_distributed()) return
        comm%MPI_VAL = grid%comm
        failed = merge(grid%rank, huge(1), allocated(error))
        call MPI_Allreduce(failed, first, 1, MPI_INTEGER, MPI_MIN, comm)
        if (first == huge(1)) return
        n = 0
        if (grid%rank == first) n = [len(error%message), error%category]
        call MPI_Bcast(n, 2, MPI_INTEGER, first, comm)
        allocate (character(len=n(1)) :: msg)
        if (grid%rank == first) msg = error%message
        call MPI_Bcast(msg, n(1), MPI_CHARACTER, first, comm)
        if (.not. allocated(error)) call fatal_error(error, msg, n(2))
#endif
    end subroutine share_error

end module veslide_collective
