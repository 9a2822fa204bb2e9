!> Bound-constrained conjugate gradient (BCCG) with an FFT preconditioner, for the contact
!> problem of a symmetric operator: the elastic solver, and the inner solver of `solver_pdr`.
!>
!> Vollebregt, "The bound-constrained conjugate gradient method for non-negative matrices",
!> J. Optim. Theory Appl. 162 (2014) 931-953 (written from the paper and from the description of
!> the CONTACT code's routine normcg; no code taken). Against Polonsky-Keer it differs in three
!> ways, which together make its iteration count almost independent of the grid:
!>  - the residual is preconditioned by the inverse multiplier 1/M of the operator (exact for
!>    full contact; on a partial contact set it removes the 1/|q| spread of the spectrum);
!>  - the conjugacy is not restarted when points enter or leave the contact set: points whose
!>    pressure would become negative are clipped and leave the set, points outside it whose gap
!>    became negative join it with their residual, and the direction simply loses its component
!>    outside the set;
!>  - the load constraint is kept by the direction: its sum over the contact set is zero (z and
!>    the previous direction are projected by subtracting their means over the set), so a step
!>    only moves pressure within the set; the pressure is rescaled after a step only for what
!>    the clipping added. Rescaling after every step instead (an earlier version) fought the
!>    conjugate directions: about 4 % of one-row elastic profiles stalled with a tilted gap
!>    over a correct contact set (20000 iterations), and some viscoelastic ones inside `pdr`;
!>    projected, every profile of the `hard` suite converges (at most 36 iterations elastic),
!>    elastic 2-D scenes take the same iterations, and `pdr` 1-7 % more FFT pairs on 2-D
!>    viscoelastic scenes (the paper scene at 256^2: 385 -> 399).
!>
!> In units p/p_mean and h/h_s, the problem is: P >= 0, mean P = 1, g = M P - H + d >= 0,
!> P g = 0, with M a real, even, non-negative multiplier (zero on the mean mode) and H the
!> heights, both given on the half-spectrum. The state is kept exact: every iteration recomputes
!> the gap g = M P - H from the transform of the new pressure, so no error accumulates and no
!> correction for the clipped points is needed. Per iteration: one FFT pair for the
!> preconditioner, one forward transform of the direction (its energy v.Mv by Parseval), one
!> forward transform of the new pressure and one inverse for the new gap: 2.5 FFT pairs, and
!> five fused passes over the grid (residual statistics; residual and admissions; the sum of z
!> over the set; direction; step and clipping). Every sum is taken row by row (or column by column of the spectrum's
!> storage) and then over the rows in order (veslide_collective), so the path is the same for
!> any number of threads, and for any number of processes on a distributed grid.
module veslide_solver_bccg
    use, intrinsic :: iso_fortran_env, only: i8 => int64
    use veslide_kinds, only: dp
    use veslide_grid, only: grid_t
    use veslide_collective, only: ordered_sum, ordered_sum_scalar, global_min, global_count, gather_all
    use veslide_arrays, only: rarray_t, carray_t, iarray_t
    use veslide_transform, only: transform_t
    use veslide_device, only: device_failed
    use veslide_passes, only: fill, scale, divide, subtract, row_sums, complex_scale, complex_add, &
                              complex_divide, centre_scale, zero_mean_mode
    use veslide_contact_law, only: contact_law_t, LAW_HARD_WALL
    use veslide_contact_passes, only: project_and_sum
    use veslide_bccg_passes, only: metric_t, metric, set_contact, statistics, residual, precondition, set_sum, direction, energy, &
                                   step, update_transform, step_transform, gap_multiply, add_points, clipped_points, &
                                   max_points
    use veslide_contact, only: contact_problem_t, contact_state_t, contact_fields_t
    use veslide_solver_options, only: solver_options_t, progress_ticker_t
    implicit none
    private
    public :: bccg_t, bccg_solve

    !> The one contact law BCCG takes (an active-set method for its bounds p >= 0, g >= 0;
    !> veslide_solver_table): its passes apply the hard wall's maps
    type(contact_law_t), parameter :: hard_wall = contact_law_t(kind=LAW_HARD_WALL)

    !> One symmetric contact operator with its preconditioner, heights and work arrays (reused
    !> by an outer iteration that solves many problems with the same operator), held where the
    !> solve runs (veslide_arrays)
    type :: bccg_t
        type(grid_t) :: grid                   !! the grid (distributed or not)
        integer :: nx = 0, ny = 0              !! ny: this process's rows
        real(dp) :: cells = 0.0_dp             !! N = nx ny, the whole grid's cells
        logical :: device = .false.            !! the arrays are on the device
        type(metric_t) :: ks                   !! M/N on the spectral storage (grid%spectral_shape):
                                               !! an array on the host, formed from K_d where read
                                               !! on the device (veslide_bccg_passes); the
                                               !! preconditioner 1/(M N) = 1/(ks N^2) is taken
                                               !! from it where used (4 bytes per cell fewer)
        !> Hermitian weights as a product wa(a) wb(b) over the storage positions (a, b); wa also
        !> where the solve runs (wa_dev, (na, 1))
        real(dp), allocatable :: wa(:), wb(:)
        type(rarray_t) :: wa_dev
        type(carray_t) :: hk                   !! transform of the heights / N
        type(rarray_t) :: v                    !! search direction (zero outside the contact set)
        type(iarray_t) :: act                  !! the contact set (1 in it, 0 outside)
        type(carray_t) :: pk                   !! transform of the pressure (kept along: no drift
                                               !! beyond round-off, and no correction FFT needed)
        type(carray_t) :: exy                  !! on the device: the clipped points' factors
                                               !! (add_points' work array, (nx/2 + 1 + ny) x max_points)
        logical :: pk_valid = .false.          !! pk is the transform of the last returned pressure
        real(dp) :: pairs = 0.0_dp             !! FFT pairs spent (a single transform counts 1/2)
        ! residual measures of the last solve (dimensionless, as in veslide_contact)
        real(dp) :: penetration = huge(1.0_dp), complementarity = huge(1.0_dp), load_error = huge(1.0_dp)
        real(dp) :: residual = huge(1.0_dp)
        real(dp) :: approach = 0.0_dp          !! d = -mean of M P - H over the contact set
    contains
        procedure :: init => bccg_init
        procedure :: set_heights => bccg_set_heights
        procedure :: solve => bccg_core
        procedure :: destroy => bccg_destroy
    end type bccg_t

contains

    !> Set up for the grid of the transform `t`, on its backend; the caller sets `ks` to the
    !> symmetric multiplier M/N (real, >= 0, zero on the mean mode; `metric`)
    subroutine bccg_init(self, t, grid)
        class(bccg_t), intent(inout) :: self
        type(transform_t), intent(in) :: t
        type(grid_t), intent(in) :: grid
        integer :: i, sh(2)
        call self%destroy()
        self%grid = grid
        self%device = t%device
        self%nx = t%nx; self%ny = t%x%n2
        self%cells = grid%cells()
        sh = grid%spectral_shape()
        if (grid%transposed) then
            self%wa = [(1.0_dp, i=1, sh(1))]
            self%wb = [(grid%hermitian_weight(grid%i0 + i), i=1, sh(2))]
        else
            self%wa = [(grid%hermitian_weight(i), i=1, sh(1))]
            self%wb = [(1.0_dp, i=1, sh(2))]
        end if
        call self%wa_dev%create(sh(1), 1, self%device)
        call self%wa_dev%upload(reshape(self%wa, [sh(1), 1]))
        call self%v%create(self%nx, self%ny, self%device)
        call self%act%create(self%nx, self%ny, self%device)
        call self%hk%create(sh(1), sh(2), self%device)
        call self%pk%create(sh(1), sh(2), self%device)
        if (self%device) call self%exy%create(sh(1) + sh(2), max_points, .true.)
        self%pk_valid = .false.
        self%pairs = 0.0_dp
    end subroutine bccg_init

    subroutine bccg_destroy(self)
        class(bccg_t), intent(inout) :: self
        call self%ks%destroy(); call self%wa_dev%destroy(); call self%v%destroy(); call self%act%destroy()
        call self%hk%destroy(); call self%pk%destroy(); call self%exy%destroy()
        self%pk_valid = .false.
    end subroutine bccg_destroy

    !> Heights H = (h - offset) scale (dimensionless, any mean): their transform / N (one forward
    !> transform)
    subroutine bccg_set_heights(self, t, h, offset, scale)
        class(bccg_t), intent(inout) :: self
        type(transform_t), intent(inout) :: t
        type(rarray_t), intent(in) :: h
        real(dp), intent(in) :: offset, scale
        call centre_scale(t%x, h, offset, scale)
        call t%forward()
        call self%hk%assign(t%k)
        call complex_divide(self%hk, self%cells)
        if (self%grid%owns_mean_mode()) call zero_mean_mode(self%hk)
        self%pairs = self%pairs + 0.5_dp
    end subroutine bccg_set_heights

    !> Solve from the start `p` (>= 0, positive sum; rescaled to mean 1) until the residual is at
    !> most `tol` or `max_it` iterations were spent (counted in `its`). On exit `p` is the
    !> pressure (mean 1, >= 0) and t%x holds the gap M p - H + d of it. `same_start`: p is the
    !> pressure this object returned last (its transform is reused: half an FFT pair saved).
    subroutine bccg_core(self, t, p, tol, max_it, its, same_start, ticker)
        class(bccg_t), intent(inout) :: self
        type(transform_t), intent(inout) :: t
        type(rarray_t), intent(inout) :: p
        real(dp), intent(in) :: tol
        integer, intent(in) :: max_it
        integer, intent(inout) :: its
        logical, intent(in), optional :: same_start
        !> told each iteration (a solve of its own; an outer iteration reports for itself)
        type(progress_ticker_t), intent(inout), optional :: ticker
        integer, parameter :: max_direct = max_points    ! clipped points transformed directly, not by FFT
        real(dp) :: n, n2, a, a_new, gprev, s1, gmin, spg, sp, c1, gbar, rz, rz_old, beta, rv, rvo, vkv, alpha
        real(dp) :: sr, mv, mz, t3(3), t4(4), m3(3)
        real(dp), allocatable :: rows(:, :), rows4(:, :), cols(:), clip_rows(:), pts(:, :)
        integer :: nb, ny, nclip
        integer(i8) :: nact, cnt(1)
        logical :: restart, restarted, reuse

        ny = self%ny
        nb = self%ks%n2
        n = self%cells; n2 = n*n
        allocate (rows(3, ny), rows4(4, ny), cols(nb), clip_rows(ny))
        reuse = .false.
        if (present(same_start)) reuse = same_start .and. self%pk_valid
        if (.not. reuse) then
            call project_and_sum(hard_wall, p, rows(1, :))
            sp = ordered_sum_scalar(self%grid, rows(1, :))
            if (.not. (sp > 0.0_dp)) then
                call fill(p, 1.0_dp); sp = n
            end if
            call t%x%assign(p)
            call t%forward()
            call self%pk%assign(t%k)
            self%pairs = self%pairs + 0.5_dp
        else
            call row_sums(p, rows(1, :))
            sp = ordered_sum_scalar(self%grid, rows(1, :))
        end if
        a = n/sp                      ! the true pressure is a p
        call set_contact(self%act, p)
        call gap_from_transform(a)
        call fill(self%v, 0.0_dp); rz_old = 1.0_dp; restart = .true.
        gprev = 0.0_dp
        do
            ! pass 1: statistics of g = t%x - gprev: contact-set mean, residual measures
            call statistics(t%x, self%act, p, gprev, rows, nact, gmin)
            call ordered_sum(self%grid, rows, t3)
            cnt(1) = nact; call global_count(self%grid, cnt); nact = cnt(1)
            call global_min(self%grid, gmin)
            s1 = t3(1); spg = t3(2); sp = t3(3)
            c1 = s1/real(max(nact, 1_i8), dp)
            gbar = gprev + c1
            self%approach = -gbar
            ! the law's measures in the units of the solve (h_s = p_mean = 1; p >= 0 is kept)
            m3 = hard_wall%measures(gmin - c1, a*(spg - c1*sp), a*sp, 0.0_dp, 1.0_dp, 1.0_dp)
            self%penetration = m3(1)
            self%complementarity = m3(2)
            self%load_error = abs(a*sp/n - 1.0_dp)
            self%residual = max(self%penetration, self%complementarity, self%load_error)
            gprev = gbar
            if (self%residual <= tol .or. its >= max_it) exit
            its = its + 1
            if (present(ticker)) call ticker%tick(its, self%residual, ceiling(self%pairs))

            ! pass 2: residual r on the contact set, with the points outside it that penetrate
            ! (into the FFT buffer; r is not kept: r.v needs only r.z, by Parseval, and r.v_old),
            ! and the sums over the (grown) set that project the direction below
            call residual(t%x, self%act, self%v, gbar, rows4)
            call ordered_sum(self%grid, rows4, t4)
            rvo = t4(1); sr = t4(2); mv = t4(3)/max(t4(4), 1.0_dp)

            ! preconditioned residual z = M^-1 r (one FFT pair), and r.z by Parseval
            call t%forward()
            call precondition(t%k, self%ks, self%wa, self%wa_dev, self%wb, n2, cols)
            rz = ordered_sum_scalar(self%grid, cols, spectral=.true.)
            call t%backward_unscaled()
            self%pairs = self%pairs + 1.0_dp

            ! the direction keeps the load: zero sum over the set, so that a step moves pressure
            ! within the set instead of adding or removing it (z and v_old projected by taking
            ! their means over the set; r.(z - mz) = r.z - mz sum r)
            call set_sum(t%x, self%act, rows(1, :))
            mz = ordered_sum_scalar(self%grid, rows(1, :))/max(t4(4), 1.0_dp)
            rz = rz - mz*sr
            beta = 0.0_dp
            if (.not. restart .and. rz_old > 0.0_dp) beta = rz/rz_old
            restarted = restart                 ! this direction is the projected residual alone
            rz_old = rz; restart = .false.

            ! pass 3: direction v = (z - mz) + beta (v - mv) on the contact set, zero outside
            rv = rz + beta*(rvo - mv*sr)
            call direction(t%x, self%act, self%v, beta, mz + beta*mv)

            ! v.Mv by Parseval (one forward transform; t%k keeps v^)
            call t%forward()
            call energy(t%k, self%ks, self%wa, self%wa_dev, self%wb, cols)
            vkv = ordered_sum_scalar(self%grid, cols, spectral=.true.)
            self%pairs = self%pairs + 0.5_dp
            if (.not. (vkv > 0.0_dp) .or. .not. (rv > 0.0_dp)) then
                ! no descent along v (round-off, or a direction without energy): restart from
                ! the preconditioned residual; the end when that has none either
                if (restarted) exit
                restart = .true.; call fill(self%v, 0.0_dp)
                call gap_from_transform(a)
                cycle
            end if
            alpha = rv/vkv

            ! pass 4: step and clipping (points leave the set; the clipped amounts c go to the
            ! FFT buffer), the load kept by the pending factor
            call step(t%x, self%act, p, self%v, a, alpha, rows(1, :), nclip, clip_rows)
            sp = ordered_sum_scalar(self%grid, rows(1, :))
            call global_count(self%grid, nclip)
            if (.not. (sp > 0.0_dp)) exit
            a_new = n/sp

            ! the transform of the new pressure a p + alpha v + c: the step's part from v^, the
            ! clipped part c from its own transform (or directly, for a few points); then the gap
            if (nclip == 0) then
                call step_transform(self%pk, t%k, self%ks, self%hk, a, alpha, a_new)
                call t%backward_unscaled()
                self%pairs = self%pairs + 0.5_dp
            else
                call update_transform(self%pk, t%k, a, alpha)
                if (nclip <= max_direct) then
                    call gather_clipped_points()
                    call add_points(self%pk, pts, self%grid, self%exy)
                else
                    call t%forward()
                    self%pairs = self%pairs + 0.5_dp
                    call complex_add(self%pk, t%k)
                end if
                call gap_from_transform(a_new)
            end if
            a = a_new
        end do
        ! the pressure with its load (and its transform), and its gap (t%x = a M p - H, shifted
        ! by the approach)
        call scale(p, a)
        call complex_scale(self%pk, a)
        self%pk_valid = .true.
        call subtract(t%x, gbar)

    contains

        !> t%x = a M p - H from the transform self%pk of p (half an FFT pair)
        subroutine gap_from_transform(a)
            real(dp), intent(in) :: a
            call gap_multiply(t%k, self%pk, self%ks, self%hk, a)
            call t%backward_unscaled()
            self%pairs = self%pairs + 0.5_dp
        end subroutine gap_from_transform

        !> pts(:, k) = (i, j, value) of the clipped points held in t%x, every process's, in the
        !> order of the whole grid (j the global row)
        subroutine gather_clipped_points()
            real(dp) :: mine(3, max_direct)
            integer :: k
            call clipped_points(t%x, clip_rows, self%grid%j0, max_direct, mine, k)
            call gather_all(self%grid, mine(:, 1:k), pts)
        end subroutine gather_clipped_points

    end subroutine bccg_core

    !> The elastic contact problem (a symmetric kernel) by BCCG, on the fields `f` (host or
    !> device). The internal measures are those of veslide_contact on the gap the iteration
    !> carries; convergence is confirmed on a fresh K p by `problem%confirm` (and the internal
    !> tolerance tightened if that disagrees).
    subroutine bccg_solve(problem, f, opts, state)
        type(contact_problem_t), intent(in) :: problem
        type(contact_fields_t), intent(inout) :: f
        type(solver_options_t), intent(in) :: opts
        !> on entry the starting pressure (problem%start, in f%p); on exit the solution
        type(contact_state_t), intent(inout) :: state
        type(bccg_t) :: b
        real(dp) :: hs, p_mean, tol
        integer :: its
        type(progress_ticker_t) :: ticker

        hs = problem%height_scale_m
        p_mean = problem%p_mean_pa
        state%method = 'bccg'
        call ticker%start(opts, 'bccg')
        call b%init(f%t, problem%kernel%grid)
        call metric(b%ks, f%kd, (p_mean/hs)/problem%kernel%grid%cells(), modulus=.false.)
        call b%set_heights(f%t, f%h, problem%h_mean, 1.0_dp/hs)
        tol = opts%tolerance
        its = 0
        state%operator_applications = 0
        ! solved in place in units of p_mean (no copy of the pressure)
        call divide(f%p, p_mean)
        do
            call b%solve(f%t, f%p, tol, opts%max_iterations, its, ticker=ticker)
            call scale(f%p, p_mean)
            call problem%confirm(f, state, opts%tolerance)
            if (state%converged) exit
            if (its >= opts%max_iterations .or. tol < 1.0e-15_dp .or. f%device .and. device_failed()) exit
            tol = tol/10.0_dp
            call divide(f%p, p_mean)
        end do
        state%iterations = its
        state%operator_applications = state%operator_applications + ceiling(b%pairs)
        call b%destroy()
    end subroutine bccg_solve

end module veslide_solver_bccg
