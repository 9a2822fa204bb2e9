!> Threads that never make a solve slower than one thread would.
!>
!> On a shared machine another process may hold one of the cores the run's threads were given;
!> every parallel pass then waits for the thread that shares its core, and two threads can be
!> slower than one (docs/solver-scaling.md). The governor watches each iteration of a solve: its
!> wall time and the process's involuntary context switches (the kernel taking a core from a
!> thread for another task; none on a quiet machine, hundreds per second when a core is shared).
!> When the switches say a core is shared, it times a few iterations on one thread and keeps
!> whichever was faster for a while (`hold` iterations, doubled each time the same answer comes
!> back), then looks again. On a quiet machine it never leaves the run's thread count. The results
!> do not depend on it: every sum and transform is the same on any number of threads.
module veslide_threads
    use, intrinsic :: iso_c_binding, only: c_long_long
    !$ use omp_lib, only: omp_get_max_threads, omp_set_num_threads
    use veslide_kinds, only: dp
    use veslide_clock, only: wall_seconds
    implicit none
    private
    public :: thread_governor_t, restore_threads, threaded, parallel_cells

    !> A pass over the grid runs on all the threads from this many cells up (this process's), and
    !> on one below, or on a field of one row (the rows are the work the threads share): a
    !> parallel region costs more than a pass of fewer cells with the passive wait, measured on
    !> 2 cores (docs/solver-scaling.md, Small grids and one-row profiles: pdr 1.4 times slower
    !> on two threads than on one at 128^2, 1.1 at 256^2, 5 to 6 on a one-row profile of 8192
    !> cells; faster from 512^2). The results are the same bits either way
    integer, parameter :: parallel_cells = 131072

    integer, parameter :: RUN_ALL = 1, PROBE_ONE = 2, HOLD = 3
    integer, parameter :: window = 3                  !! iterations per measurement
    integer, parameter :: hold_min = 10, hold_max = 320
    real(dp), parameter :: min_iteration_s = 2.0e-3_dp  !! shorter iterations are not governed
    real(dp), parameter :: max_switch_rate = 100.0_dp   !! involuntary switches per second of a quiet run

    !> the run's thread count while the governor has lowered it (0: not lowered)
    integer, save :: lowered_from = 0

    type :: thread_governor_t
        integer :: nominal = 1          !! the run's threads
        integer :: current = 1          !! threads of the next iteration
        integer :: phase = RUN_ALL      !! watching on all threads, timing one thread, or holding
        integer :: winner = 0           !! threads of the last decision (0: none yet)
        integer :: left = 0             !! iterations left to hold it
        integer :: hold = hold_min      !! iterations a decision holds (doubled when repeated)
        integer :: n = 0                !! iterations in the current window
        real(dp) :: t = 0.0_dp, cs = 0.0_dp   !! their time [s] and involuntary switches
        real(dp) :: t_all = 0.0_dp, t_one = 0.0_dp   !! last times per iteration [s] (0: unknown)
        real(dp) :: last = -1.0_dp      !! clock at the previous iteration's end
        real(dp) :: cs_last = 0.0_dp
    contains
        procedure :: start => governor_start
        procedure :: tick => governor_tick
        procedure :: decide => governor_decide
    end type thread_governor_t

    interface
        integer(c_long_long) function c_switches() bind(c, name='veslide_involuntary_switches')
            import :: c_long_long
        end function c_switches
    end interface

contains

    !> Does a pass over `cells` cells in `rows` rows run on all the threads (parallel_cells)?
    pure logical function threaded(cells, rows)
        integer, intent(in) :: cells, rows
        threaded = cells >= parallel_cells .and. rows > 1
    end function threaded

    !> The run's threads back, if a governor lowered them (at the end of a solve)
    subroutine restore_threads()
        !$ if (lowered_from > 0) call omp_set_num_threads(lowered_from)
        lowered_from = 0
    end subroutine restore_threads

    !> Start watching a solve on the run's threads
    subroutine governor_start(self)
        class(thread_governor_t), intent(out) :: self
        call restore_threads()
        self%nominal = 1
        !$ self%nominal = omp_get_max_threads()
        self%current = self%nominal
        self%last = wall_seconds(); self%cs_last = real(c_switches(), dp)
    end subroutine governor_start

    !> One iteration done: measure it and set the threads of the next
    subroutine governor_tick(self)
        class(thread_governor_t), intent(inout) :: self
        real(dp) :: now, cs
        integer :: before
        if (self%nominal <= 1) return
        now = wall_seconds(); cs = real(c_switches(), dp)
        before = self%current
        call self%decide(now - self%last, cs - self%cs_last)
        self%last = now; self%cs_last = cs
        if (self%current /= before) then
            !$ call omp_set_num_threads(self%current)
            lowered_from = merge(self%nominal, 0, self%current < self%nominal)
        end if
    end subroutine governor_tick

    !> The decision alone (no clock, no OpenMP): the last iteration took `dt` seconds with
    !> `switches` involuntary context switches; sets `current` for the next one
    subroutine governor_decide(self, dt, switches)
        class(thread_governor_t), intent(inout) :: self
        real(dp), intent(in) :: dt, switches
        if (self%nominal <= 1) return
        self%n = self%n + 1; self%t = self%t + dt; self%cs = self%cs + switches
        select case (self%phase)
        case (RUN_ALL)
            if (self%n < window) return
            self%t_all = self%t/self%n
            if (self%t_all >= min_iteration_s .and. self%cs/self%t > max_switch_rate) then
                ! a core is shared: one thread, if it was faster when last timed; else time it
                if (self%t_one > 0.0_dp .and. self%t_one < self%t_all) then
                    call hold_on(1)
                else
                    self%phase = PROBE_ONE; self%current = 1
                end if
            end if
        case (PROBE_ONE)
            if (self%n < window) return
            self%t_one = self%t/self%n
            call hold_on(merge(1, self%nominal, self%t_one < self%t_all))
        case (HOLD)
            self%left = self%left - 1
            if (self%n >= window) then
                if (self%current == 1) then
                    self%t_one = self%t/self%n
                else
                    self%t_all = self%t/self%n
                end if
            end if
            if (self%left > 0) then
                if (self%n < window) return
            else
                self%phase = RUN_ALL; self%current = self%nominal
            end if
        end select
        self%n = 0; self%t = 0.0_dp; self%cs = 0.0_dp

    contains

        !> Run on k threads for `hold` iterations; a decision repeated holds twice as long
        subroutine hold_on(k)
            integer, intent(in) :: k
            if (k == self%winner) then
                self%hold = min(2*self%hold, hold_max)
            else
                self%hold = hold_min
            end if
            self%winner = k; self%current = k
            self%phase = HOLD; self%left = self%hold
        end subroutine hold_on

    end subroutine governor_decide

end module veslide_threads
