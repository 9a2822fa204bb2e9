!> Polonsky & Keer (1999) constrained conjugate gradient for the symmetric (elastic) contact
!> problem, load control. The displacement is updated linearly (u <- s (u - tau K t)), so an
!> iteration costs one operator application (one FFT pair) unless the active set changed, when the
!> correction K c of the clipped/re-admitted points costs one more.
!> It is an active-set method for the hard wall, the one contact law it takes
!> (veslide_solver_table): its loops apply the hard wall's maps (what counts as contact, the
!> pressure bound it clips at, the gap bound it re-admits cells by; veslide_contact_law_maps.inc).
!> Polonsky & Keer, Wear 231 (1999) 206-219.
module veslide_solver_pk
    use veslide_kinds, only: dp
    use veslide_fftw, only: fft2d_t
    use veslide_contact, only: contact_problem_t, contact_state_t, residual_measures
    use veslide_solver_options, only: solver_options_t, progress_ticker_t
    use veslide_collective, only: ordered_sum, global_min
    use veslide_threads, only: threaded
    implicit none
    private
    public :: polonsky_keer

contains

    !> Polonsky & Keer (1999) constrained conjugate gradient, load control.
    !>
    !> The iteration is memory-bound outside its one FFT pair, so it is written as four fused,
    !> OpenMP-parallel passes over the grid and keeps no gap array:
    !>   A  residuals, contact-set mean of the gap and |g|^2 (sums shifted by the previous mean,
    !>      so that no cancellation spoils them near convergence);
    !>   C  conjugate direction t, written straight into the FFT buffer, with sum(g t), sum(t);
    !>   -  r = K t (the FFT pair);
    !>   D  step-length sums;  E  step, projection p >= 0, re-admission, u <- u - tau r.
    !> The load rescaling p, u <- s p, s u is kept as a pending scalar `a` (true p = a P). The
    !> displacement is carried along linearly; the correction K c for the points that projection
    !> or re-admission changed costs one more FFT pair in the iterations that have any, unless
    !> there is a single such point (then one shifted column of the influence function is added,
    !> on one process). Every sum is taken row by row and then over the rows in order, so the
    !> iteration is the same whatever the number of threads or processes.
    subroutine polonsky_keer(problem, fft, opts, state)
        type(contact_problem_t), intent(in) :: problem
        type(fft2d_t), intent(inout) :: fft
        type(solver_options_t), intent(in) :: opts
        !> on entry the starting pressure (problem%start); on exit the solution
        type(contact_state_t), intent(inout) :: state
        real(dp), allocatable :: t(:, :), green(:, :), rows(:, :)
        real(dp) :: a, gp, gbar, s1, s2, gg, gg_old, beta, tau, den, num, sr, srt, st, sp_new, pv, g, pn, hs
        real(dp) :: gmin, spg, sp, pmin, c1, delta, uo, c, p_mean, nc, m, noverlap, tot(5), ext(2), cells
        real(dp) :: r1, r2, r3, r4, r5, e1, e2
        integer :: nx, ny, i, j, since_fresh, ic, jc
        logical :: fresh, have_green
        type(progress_ticker_t) :: ticker

        call ticker%start(opts, 'pk')
        nx = size(problem%h, 1); ny = size(problem%h, 2)
        hs = problem%height_scale_m
        p_mean = problem%p_mean_pa
        state%method = 'pk'
        associate (grid => problem%kernel%grid)
        cells = grid%cells()
        allocate (t(nx, ny), rows(5, ny))
        have_green = .false.
        call problem%kernel%apply(fft, state%p, state%u)
        state%operator_applications = 1
        fresh = .true.; since_fresh = 0
        t = 0.0_dp; delta = 0.0_dp; gg_old = 1.0_dp; a = 1.0_dp
        do j = 1, ny
            rows(1, j) = sum(state%u(:, j) - (problem%h(:, j) - problem%h_mean), &
                             mask=hard_wall_in_contact(state%p(:, j)))
            rows(2, j) = count(hard_wall_in_contact(state%p(:, j)))
        end do
        call ordered_sum(grid, rows(1:2, :), tot(1:2))
        gp = tot(1)/max(1.0_dp, tot(2))
        do
            ! pass A: residuals and contact-set statistics of g = a U - h, shifted by gp
            ext = huge(1.0_dp)
            !$omp parallel do schedule(guided) if (threaded(nx*ny, ny)) &
            !$omp& private(i, pv, g, r1, r2, r3, r4, r5, e1, e2) reduction(min:ext)
            do j = 1, ny
                r1 = 0.0_dp; r2 = 0.0_dp; r3 = 0.0_dp; r4 = 0.0_dp; r5 = 0.0_dp
                e1 = huge(1.0_dp); e2 = huge(1.0_dp)
                do i = 1, nx
                    pv = a*state%p(i, j)
                    g = a*state%u(i, j) - (problem%h(i, j) - problem%h_mean) - gp
                    if (hard_wall_in_contact(pv)) then
                        r1 = r1 + 1.0_dp; r2 = r2 + g; r3 = r3 + g*g
                    end if
                    e1 = min(e1, g)
                    r4 = r4 + pv*g
                    r5 = r5 + pv
                    e2 = min(e2, pv)
                end do
                rows(:, j) = [r1, r2, r3, r4, r5]
                ext = min(ext, [e1, e2])
            end do
            !$omp end parallel do
            call ordered_sum(grid, rows, tot)
            call global_min(grid, ext)
            nc = tot(1); s1 = tot(2); s2 = tot(3); spg = tot(4); sp = tot(5); gmin = ext(1); pmin = ext(2)
            c1 = s1/nc
            gbar = gp + c1
            gg = max(s2 - s1*c1, 0.0_dp)
            state%approach_m = -gbar
            call residual_measures(problem%law, state, gmin - c1, spg - c1*sp, sp, pmin, sp, cells, p_mean, hs)
            gp = gbar
            if (state%residual <= opts%tolerance) then
                if (fresh) then
                    state%converged = .true.; exit
                end if
                call refresh(); cycle
            end if
            if (state%iterations >= opts%max_iterations) exit
            state%iterations = state%iterations + 1
            call ticker%tick(state%iterations, state%residual, state%operator_applications)

            ! pass C: conjugate direction on the contact set, straight into the FFT buffer
            beta = delta*gg/gg_old
            gg_old = gg
            !$omp parallel do schedule(guided) if (threaded(nx*ny, ny)) private(i, g, r1, r2)
            do j = 1, ny
                r1 = 0.0_dp; r2 = 0.0_dp
                do i = 1, nx
                    if (hard_wall_in_contact(state%p(i, j))) then
                        g = a*state%u(i, j) - (problem%h(i, j) - problem%h_mean) - gbar
                        t(i, j) = g + beta*t(i, j)
                        r1 = r1 + g*t(i, j)
                        r2 = r2 + t(i, j)
                    else
                        t(i, j) = 0.0_dp
                    end if
                    fft%x(i, j) = t(i, j)
                end do
                rows(1:2, j) = [r1, r2]
            end do
            !$omp end parallel do
            call ordered_sum(grid, rows(1:2, :), tot(1:2))
            num = tot(1); st = tot(2)
            call problem%kernel%apply_buffer(fft)          ! fft%x = r = K t
            state%operator_applications = state%operator_applications + 1

            ! pass D: step length, with r centred on the contact set
            !$omp parallel do schedule(guided) if (threaded(nx*ny, ny)) private(i, r1, r2)
            do j = 1, ny
                r1 = 0.0_dp; r2 = 0.0_dp
                do i = 1, nx
                    if (hard_wall_in_contact(state%p(i, j))) then
                        r1 = r1 + fft%x(i, j)
                        r2 = r2 + fft%x(i, j)*t(i, j)
                    end if
                end do
                rows(1:2, j) = [r1, r2]
            end do
            !$omp end parallel do
            call ordered_sum(grid, rows(1:2, :), tot(1:2))
            sr = tot(1); srt = tot(2)
            den = srt - sr/nc*st
            if (.not. (den > 0.0_dp)) then
                ! no descent left: only round-off remains, confirm on a fresh product
                if (fresh) exit
                call refresh(); cycle
            end if
            tau = num/den

            ! pass E: step, projection, re-admission of overlapping points, displacement update.
            ! r is not needed after its use here, so the buffer takes the correction c (what
            ! projection and re-admission add to the linear step).
            ic = 0; jc = 0
            !$omp parallel do schedule(guided) if (threaded(nx*ny, ny)) private(i, pn, g, uo, c, r1, r2, r3) reduction(max:ic, jc)
            do j = 1, ny
                r1 = 0.0_dp; r2 = 0.0_dp; r3 = 0.0_dp
                do i = 1, nx
                    uo = a*state%u(i, j)
                    pn = a*state%p(i, j) - tau*t(i, j)
                    state%u(i, j) = uo - tau*fft%x(i, j)
                    c = 0.0_dp
                    if (hard_wall_below(pn)) then
                        c = -pn
                        pn = hard_wall_project(pn)
                    end if
                    if (pn == 0.0_dp) then            ! (at the bound: re-admitted where it penetrates)
                        g = uo - (problem%h(i, j) - problem%h_mean) - gbar
                        if (hard_wall_penetrates(g)) then
                            r3 = r3 + 1.0_dp
                            c = c - tau*g
                            pn = -tau*g
                        end if
                    end if
                    fft%x(i, j) = c
                    if (c /= 0.0_dp) then
                        r1 = r1 + 1.0_dp; ic = max(ic, i); jc = max(jc, j)
                    end if
                    state%p(i, j) = pn
                    r2 = r2 + pn
                end do
                rows(1:3, j) = [r1, r2, r3]
            end do
            !$omp end parallel do
            call ordered_sum(grid, rows(1:3, :), tot(1:3))
            m = tot(1); sp_new = tot(2); noverlap = tot(3)
            delta = merge(0.0_dp, 1.0_dp, noverlap > 0.0_dp)
            if (m > 0.0_dp) call add_correction(m, ic, jc)
            a = p_mean*cells/sp_new
            fresh = .false.
            since_fresh = since_fresh + 1
            if (since_fresh >= opts%refresh_every) call refresh()
        end do
        state%p = a*state%p
        state%u = a*state%u
        state%g = state%u - (problem%h - problem%h_mean) - gbar
        end associate

    contains

        !> U = K P exactly, with the pending scale applied first
        subroutine refresh()
            state%p = a*state%p; a = 1.0_dp
            call problem%kernel%apply(fft, state%p, state%u)
            state%operator_applications = state%operator_applications + 1
            fresh = .true.; since_fresh = 0
        end subroutine refresh

        !> u += K c for the correction held in the FFT buffer (m non-zeros; for m = 1 at (ic, jc))
        subroutine add_correction(m, ic, jc)
            real(dp), intent(in) :: m
            integer, intent(in) :: ic, jc
            integer :: ii, jj, i0, j0, js
            real(dp) :: cv
            if (m > 1.0_dp .or. problem%kernel%grid%is_distributed()) then
                call problem%kernel%apply_buffer(fft)
                state%u = state%u + fft%x
                state%operator_applications = state%operator_applications + 1
                return
            end if
            cv = fft%x(ic, jc)
            if (.not. have_green) then
                allocate (green(nx, ny))
                call problem%kernel%impulse_response(fft, green)
                have_green = .true.
                state%operator_applications = state%operator_applications + 1
            end if
            i0 = ic - 1; j0 = jc - 1
            do jj = 1, ny
                js = modulo(jj - 1 - j0, ny) + 1
                do ii = 1, i0
                    state%u(ii, jj) = state%u(ii, jj) + cv*green(nx - i0 + ii, js)
                end do
                do ii = i0 + 1, nx
                    state%u(ii, jj) = state%u(ii, jj) + cv*green(ii - i0, js)
                end do
            end do
        end subroutine add_correction

    end subroutine polonsky_keer

    include 'veslide_contact_law_maps.inc'

end module veslide_solver_pk
