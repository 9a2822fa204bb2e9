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
!>  - the load constraint is kept by rescaling the pressure after each step (a pending factor),
!>    not by projecting the direction (measured: as fast or faster, one pass fewer).
!>
!> In units p/p_mean and h/h_s, the problem is: P >= 0, mean P = 1, g = M P - H + d >= 0,
!> P g = 0, with M a real, even, non-negative multiplier (zero on the mean mode) and H the
!> heights, both given on the half-spectrum. The state is kept exact: every iteration recomputes
!> the gap g = M P - H from the transform of the new pressure, so no error accumulates and no
!> correction for the clipped points is needed. Per iteration: one FFT pair for the
!> preconditioner, one forward transform of the direction (its energy v.Mv by Parseval), one
!> forward transform of the new pressure and one inverse for the new gap: 2.5 FFT pairs, and
!> four fused passes over the grid (residual statistics; residual and admissions; direction;
!> step and clipping). Every sum is taken row by row (or column by column of the spectrum's
!> storage) and then over the rows in order (veslide_collective), so the path is the same for
!> any number of threads, and for any number of processes on a distributed grid.
module veslide_solver_bccg
    use, intrinsic :: iso_fortran_env, only: int8, i8 => int64
    use veslide_kinds, only: dp
    use veslide_fftw, only: fft2d_t
    use veslide_grid, only: grid_t
    use veslide_collective, only: ordered_sum, ordered_sum_scalar, global_min, global_count, gather_all
    use veslide_fields, only: field_sum
    use veslide_contact, only: contact_problem_t, contact_state_t
    use veslide_solver_options, only: solver_options_t, progress_ticker_t
    implicit none
    private
    public :: bccg_t, bccg_solve

    !> One symmetric contact operator with its preconditioner, heights and work arrays (reused
    !> by an outer iteration that solves many problems with the same operator)
    type :: bccg_t
        type(grid_t) :: grid                   !! the grid (distributed or not)
        integer :: nx = 0, ny = 0, nq = 0      !! ny: this process's rows
        real(dp) :: cells = 0.0_dp             !! N = nx ny, the whole grid's cells
        real(dp), allocatable :: ks(:, :)      !! M/N on the spectral storage (grid%spectral_shape);
                                               !! the preconditioner 1/(M N) = 1/(ks N^2) is taken
                                               !! from it where used (4 bytes per cell fewer)
        !> Hermitian weights as a product wa(a) wb(b) over the storage positions (a, b)
        real(dp), allocatable :: wa(:), wb(:)
        complex(dp), allocatable :: hk(:, :)   !! transform of the heights / N
        real(dp), allocatable :: v(:, :)       !! search direction (zero outside the contact set)
        integer(int8), allocatable :: act(:, :) !! the contact set (1 in it, 0 outside)
        complex(dp), allocatable :: pk(:, :)   !! transform of the pressure (kept along: no drift
                                               !! beyond round-off, and no correction FFT needed)
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
    end type bccg_t

contains

    !> Set up for the grid of `fft` and the symmetric multiplier `ks` = M/N (real, >= 0, zero on
    !> the mean mode) on the grid's spectral storage
    subroutine bccg_init(self, fft, ks, grid)
        class(bccg_t), intent(inout) :: self
        type(fft2d_t), intent(in) :: fft
        real(dp), intent(in) :: ks(:, :)
        type(grid_t), intent(in) :: grid
        integer :: i, sh(2)
        self%grid = grid
        self%nx = fft%nx; self%ny = size(fft%x, 2); self%nq = fft%nx/2 + 1
        self%cells = grid%cells()
        sh = grid%spectral_shape()
        self%ks = ks
        if (grid%transposed) then
            self%wa = [(1.0_dp, i=1, sh(1))]
            self%wb = [(grid%hermitian_weight(grid%i0 + i), i=1, sh(2))]
        else
            self%wa = [(grid%hermitian_weight(i), i=1, sh(1))]
            self%wb = [(1.0_dp, i=1, sh(2))]
        end if
        if (allocated(self%v)) deallocate (self%v, self%act)
        allocate (self%v(self%nx, self%ny), self%act(self%nx, self%ny))
        if (allocated(self%hk)) deallocate (self%hk, self%pk)
        allocate (self%hk(sh(1), sh(2)), self%pk(sh(1), sh(2)))
        self%hk = (0.0_dp, 0.0_dp)
        self%pk_valid = .false.
        self%pairs = 0.0_dp
    end subroutine bccg_init

    !> Heights H = (h - offset) scale (dimensionless, any mean): their transform / N (one forward
    !> transform)
    subroutine bccg_set_heights(self, fft, h, offset, scale)
        class(bccg_t), intent(inout) :: self
        type(fft2d_t), intent(inout) :: fft
        real(dp), intent(in) :: h(:, :)
        real(dp), intent(in) :: offset, scale
        fft%x = (h - offset)*scale
        call fft%forward()
        self%hk = fft%k/self%cells
        if (self%grid%owns_mean_mode()) self%hk(1, 1) = (0.0_dp, 0.0_dp)
        self%pairs = self%pairs + 0.5_dp
    end subroutine bccg_set_heights

    !> Solve from the start `p` (>= 0, positive sum; rescaled to mean 1) until the residual is at
    !> most `tol` or `max_it` iterations were spent (counted in `its`). On exit `p` is the
    !> pressure (mean 1, >= 0) and fft%x holds the gap M p - H + d of it. `same_start`: p is the
    !> pressure this object returned last (its transform is reused: half an FFT pair saved).
    subroutine bccg_core(self, fft, p, tol, max_it, its, same_start, ticker)
        class(bccg_t), intent(inout) :: self
        type(fft2d_t), intent(inout) :: fft
        real(dp), intent(inout) :: p(:, :)
        real(dp), intent(in) :: tol
        integer, intent(in) :: max_it
        integer, intent(inout) :: its
        logical, intent(in), optional :: same_start
        !> told each iteration (a solve of its own; an outer iteration reports for itself)
        type(progress_ticker_t), intent(inout), optional :: ticker
        integer, parameter :: max_direct = 8     ! clipped points transformed directly, not by FFT
        real(dp) :: n, n2, a, a_new, gprev, s1, gmin, spg, sp, c1, gbar, g, rz, rz_old, beta, rv, rvo, vkv, alpha, pt, z, w
        real(dp) :: r3(3), t3(3)
        real(dp), allocatable :: rows(:, :), cols(:), pts(:, :)
        integer :: i, j, na, nb, nx, ny, nq, nclip
        integer(i8) :: nact, cnt(1)
        logical :: restart, reuse

        nx = self%nx; ny = self%ny; nq = self%nq
        na = size(self%ks, 1); nb = size(self%ks, 2)
        n = self%cells; n2 = n*n
        allocate (rows(3, ny), cols(nb))
        reuse = .false.
        if (present(same_start)) reuse = same_start .and. self%pk_valid
        if (.not. reuse) then
            p = max(p, 0.0_dp)
            sp = field_sum(self%grid, p)
            if (.not. (sp > 0.0_dp)) then
                p = 1.0_dp; sp = n
            end if
            fft%x = p
            call fft%forward()
            self%pk = fft%k
            self%pairs = self%pairs + 0.5_dp
        else
            sp = field_sum(self%grid, p)
        end if
        a = n/sp                      ! the true pressure is a p
        self%act = merge(1_int8, 0_int8, p > 0.0_dp)
        call gap_multiply(a)
        self%v = 0.0_dp; rz_old = 1.0_dp; restart = .true.
        gprev = 0.0_dp
        do
            ! pass 1: statistics of g = fft%x - gprev: contact-set mean, residual measures
            nact = 0; gmin = huge(1.0_dp)
            !$omp parallel do schedule(guided) private(i, g, r3) reduction(+:nact) reduction(min:gmin)
            do j = 1, ny
                r3 = 0.0_dp
                do i = 1, nx
                    g = fft%x(i, j) - gprev
                    if (self%act(i, j) /= 0) then
                        nact = nact + 1; r3(1) = r3(1) + g
                    end if
                    gmin = min(gmin, g)
                    r3(2) = r3(2) + p(i, j)*g
                    r3(3) = r3(3) + p(i, j)
                end do
                rows(:, j) = r3
            end do
            !$omp end parallel do
            call ordered_sum(self%grid, rows, t3)
            cnt(1) = nact; call global_count(self%grid, cnt); nact = cnt(1)
            call global_min(self%grid, gmin)
            s1 = t3(1); spg = t3(2); sp = t3(3)
            c1 = s1/real(max(nact, 1_i8), dp)
            gbar = gprev + c1
            self%approach = -gbar
            self%penetration = max(0.0_dp, -(gmin - c1))
            self%complementarity = abs(a*(spg - c1*sp))/(a*sp)
            self%load_error = abs(a*sp/n - 1.0_dp)
            self%residual = max(self%penetration, self%complementarity, self%load_error)
            gprev = gbar
            if (self%residual <= tol .or. its >= max_it) exit
            its = its + 1
            if (present(ticker)) call ticker%tick(its, self%residual, ceiling(self%pairs))

            ! pass 2: residual r on the contact set, with the points outside it that penetrate
            ! (into the FFT buffer; r is not kept: r.v needs only r.z, by Parseval, and r.v_old)
            !$omp parallel do schedule(guided) private(i, g, w)
            do j = 1, ny
                w = 0.0_dp
                do i = 1, nx
                    g = fft%x(i, j) - gbar
                    if (self%act(i, j) == 0 .and. g < 0.0_dp) self%act(i, j) = 1_int8
                    if (self%act(i, j) /= 0) then
                        fft%x(i, j) = -g
                        w = w - g*self%v(i, j)
                    else
                        fft%x(i, j) = 0.0_dp
                    end if
                end do
                rows(1, j) = w
            end do
            !$omp end parallel do
            rvo = ordered_sum_scalar(self%grid, rows(1, :))

            ! preconditioned residual z = M^-1 r (one FFT pair), and r.z by Parseval
            call fft%forward()
            !$omp parallel do schedule(guided) private(i, w, z)
            do j = 1, nb
                z = 0.0_dp
                do i = 1, na
                    w = 0.0_dp
                    if (self%ks(i, j) > 0.0_dp) w = 1.0_dp/(self%ks(i, j)*n2)
                    z = z + self%wa(i)*w*(real(fft%k(i, j))**2 + aimag(fft%k(i, j))**2)
                    fft%k(i, j) = fft%k(i, j)*w
                end do
                cols(j) = self%wb(j)*z
            end do
            !$omp end parallel do
            rz = ordered_sum_scalar(self%grid, cols, spectral=.true.)
            call fft%backward_unscaled()
            self%pairs = self%pairs + 1.0_dp
            beta = 0.0_dp
            if (.not. restart .and. rz_old > 0.0_dp) beta = rz/rz_old
            rz_old = rz; restart = .false.

            ! pass 3: direction v = z + beta v on the contact set, zero outside
            rv = rz + beta*rvo
            !$omp parallel do schedule(guided) private(i, z)
            do j = 1, ny
                do i = 1, nx
                    if (self%act(i, j) /= 0) then
                        z = fft%x(i, j) + beta*self%v(i, j)
                    else
                        z = 0.0_dp
                    end if
                    self%v(i, j) = z
                    fft%x(i, j) = z
                end do
            end do
            !$omp end parallel do

            ! v.Mv by Parseval (one forward transform; fft%k keeps v^)
            call fft%forward()
            !$omp parallel do schedule(guided) private(i, z)
            do j = 1, nb
                z = 0.0_dp
                do i = 1, na
                    z = z + self%wa(i)*self%ks(i, j)*(real(fft%k(i, j))**2 + aimag(fft%k(i, j))**2)
                end do
                cols(j) = self%wb(j)*z
            end do
            !$omp end parallel do
            vkv = ordered_sum_scalar(self%grid, cols, spectral=.true.)
            self%pairs = self%pairs + 0.5_dp
            if (.not. (vkv > 0.0_dp) .or. .not. (rv > 0.0_dp)) then
                ! no descent along v (round-off, or a direction without energy): restart from
                ! the preconditioned residual
                if (restart) exit
                restart = .true.; self%v = 0.0_dp
                call gap_multiply(a)
                cycle
            end if
            alpha = rv/vkv

            ! pass 4: step and clipping (points leave the set; the clipped amounts c go to the
            ! FFT buffer), the load kept by the pending factor
            nclip = 0
            !$omp parallel do schedule(guided) private(i, pt, w) reduction(+:nclip)
            do j = 1, ny
                w = 0.0_dp
                do i = 1, nx
                    fft%x(i, j) = 0.0_dp
                    if (self%act(i, j) /= 0) then
                        pt = a*p(i, j) + alpha*self%v(i, j)
                        if (pt < 0.0_dp) then
                            fft%x(i, j) = -pt
                            nclip = nclip + 1
                            pt = 0.0_dp
                            self%act(i, j) = 0_int8
                            self%v(i, j) = 0.0_dp
                        end if
                    else
                        pt = 0.0_dp
                    end if
                    p(i, j) = pt
                    w = w + pt
                end do
                rows(1, j) = w
            end do
            !$omp end parallel do
            sp = ordered_sum_scalar(self%grid, rows(1, :))
            call global_count(self%grid, nclip)
            if (.not. (sp > 0.0_dp)) exit
            a_new = n/sp

            ! the transform of the new pressure a p + alpha v + c: the step's part from v^, the
            ! clipped part c from its own transform (or directly, for a few points); then the gap
            if (nclip == 0) then
                !$omp parallel do schedule(guided) private(i)
                do j = 1, nb
                    do i = 1, na
                        self%pk(i, j) = a*self%pk(i, j) + alpha*fft%k(i, j)
                        fft%k(i, j) = self%pk(i, j)*(a_new*self%ks(i, j)) - self%hk(i, j)
                    end do
                end do
                !$omp end parallel do
                call fft%backward_unscaled()
                self%pairs = self%pairs + 0.5_dp
            else
                self%pk = a*self%pk + alpha*fft%k
                if (nclip <= max_direct) then
                    call clipped_points()
                    call add_point_transforms()
                else
                    call fft%forward()
                    self%pairs = self%pairs + 0.5_dp
                    self%pk = self%pk + fft%k
                end if
                call gap_multiply(a_new)
            end if
            a = a_new
        end do
        ! the pressure with its load (and its transform), and its gap (fft%x = a M p - H, shifted
        ! by the approach)
        p = a*p
        self%pk = a*self%pk
        self%pk_valid = .true.
        fft%x = fft%x - gbar

    contains

        !> fft%x = a M p - H from the transform self%pk of p (half an FFT pair)
        subroutine gap_multiply(a)
            real(dp), intent(in) :: a
            integer :: i, j
            !$omp parallel do schedule(guided) private(i)
            do j = 1, nb
                do i = 1, na
                    fft%k(i, j) = self%pk(i, j)*(a*self%ks(i, j)) - self%hk(i, j)
                end do
            end do
            !$omp end parallel do
            call fft%backward_unscaled()
            self%pairs = self%pairs + 0.5_dp
        end subroutine gap_multiply

        !> pts(:, k) = (i, j, value) of the clipped points held in fft%x, every process's, in the
        !> order of the whole grid (j the global row)
        subroutine clipped_points()
            real(dp) :: mine(3, max_direct)
            integer :: i, j, k
            k = 0
            do j = 1, ny
                do i = 1, nx
                    if (fft%x(i, j) /= 0.0_dp .and. k < max_direct) then
                        k = k + 1
                        mine(:, k) = [real(i, dp), real(self%grid%j0 + j, dp), fft%x(i, j)]
                    end if
                end do
            end do
            call gather_all(self%grid, mine(:, 1:k), pts)
        end subroutine clipped_points

        !> pk += transform of the point values: sum_k c_k exp(-i q.x_k), the points in `pts`
        subroutine add_point_transforms()
            complex(dp), allocatable :: ex(:, :), ey(:, :)
            complex(dp) :: s
            real(dp), parameter :: two_pi = 6.283185307179586476925286766559_dp
            integer :: i, j, k, m, ij(2), a, b, ic, jc, nyg
            m = size(pts, 2); nyg = self%grid%ny
            allocate (ex(nq, m), ey(nyg, m))
            do k = 1, m
                ic = nint(pts(1, k)); jc = nint(pts(2, k))
                do i = 1, nq
                    ex(i, k) = pts(3, k)*exp(cmplx(0.0_dp, -two_pi*real(modulo((i - 1)*(ic - 1), nx), dp)/nx, dp))
                end do
                do j = 1, nyg
                    ey(j, k) = exp(cmplx(0.0_dp, -two_pi*real(modulo((j - 1)*(jc - 1), nyg), dp)/nyg, dp))
                end do
            end do
            !$omp parallel do schedule(guided) private(a, k, s, ij)
            do b = 1, nb
                do a = 1, na
                    ij = self%grid%spectral_index(a, b)
                    s = (0.0_dp, 0.0_dp)
                    do k = 1, m
                        s = s + ex(ij(1), k)*ey(ij(2), k)
                    end do
                    self%pk(a, b) = self%pk(a, b) + s
                end do
            end do
            !$omp end parallel do
        end subroutine add_point_transforms

    end subroutine bccg_core

    !> The elastic contact problem (a symmetric kernel) by BCCG. The internal measures are those
    !> of veslide_contact on the gap the iteration carries; convergence is confirmed on a fresh
    !> K p by `problem%residuals` (and the internal tolerance tightened if that disagrees).
    subroutine bccg_solve(problem, fft, opts, state)
        type(contact_problem_t), intent(in) :: problem
        type(fft2d_t), intent(inout) :: fft
        type(solver_options_t), intent(in) :: opts
        !> on entry the starting pressure (problem%start); on exit the solution
        type(contact_state_t), intent(inout) :: state
        type(bccg_t) :: b
        real(dp) :: hs, p_mean, tol
        integer :: its
        type(progress_ticker_t) :: ticker

        hs = problem%height_scale_m
        p_mean = problem%p_mean_pa
        state%method = 'bccg'
        call ticker%start(opts, 'bccg')
        call b%init(fft, real(problem%kernel%multiplier(p_mean/hs)), problem%kernel%grid)
        call b%set_heights(fft, problem%h, problem%h_mean, 1.0_dp/hs)
        tol = opts%tolerance
        its = 0
        ! solved in place in units of p_mean (no copy of the pressure)
        state%p = state%p/p_mean
        do
            call b%solve(fft, state%p, tol, opts%max_iterations, its, ticker=ticker)
            state%p = p_mean*state%p
            call problem%kernel%apply(fft, state%p, state%u)
            b%pairs = b%pairs + 1.0_dp
            call problem%residuals(state)
            if (state%residual <= opts%tolerance) then
                state%converged = .true.; exit
            end if
            if (its >= opts%max_iterations .or. tol < 1.0e-15_dp) exit
            tol = tol/10.0_dp
            state%p = state%p/p_mean
        end do
        state%iterations = its
        state%operator_applications = ceiling(b%pairs)
    end subroutine bccg_solve

end module veslide_solver_bccg
