!> The knobs of the contact solvers, the names of the methods, and the progress a long solve
!> reports: every `progress_every_s` seconds a solver tells the caller's callback (if any) its
!> iteration, its own residual measure and the FFT pairs spent. On a distributed grid those
!> numbers are the whole grid's (each process calls its own callback; the program gives one to
!> the first process only). The callback must not print from a library: the app supplies it.
!> The same tick lets the thread governor (veslide_threads) choose the threads of the next iteration.
module veslide_solver_options
    use veslide_kinds, only: dp
    use veslide_strings, only: name_index
    use veslide_clock, only: wall_seconds
    use veslide_threads, only: thread_governor_t
    implicit none
    private
    public :: solver_options_t, solver_method_id, solver_method_names
    public :: solver_progress_t, solver_progress_callback, progress_ticker_t, progress_line
    public :: SOLVER_AUTO, SOLVER_PK, SOLVER_DR, SOLVER_BCCG, SOLVER_PDR, SOLVER_GCG
    public :: DEVICE_AUTO, DEVICE_CPU, DEVICE_GPU, device_names, device_choice_id

    integer, parameter :: SOLVER_AUTO = 1, SOLVER_PK = 2, SOLVER_DR = 3, SOLVER_BCCG = 4, SOLVER_PDR = 5, &
                          SOLVER_GCG = 6
    !> Names of the methods, indexed by their SOLVER_* id (the namelist's `&solver method`)
    character(len=*), parameter :: solver_method_names(6) = [character(len=4) :: 'auto', 'pk', 'dr', 'bccg', &
                                                             'pdr', 'gcg']

    !> Where a solve runs (the namelist's `&solver device`): 'auto' the GPU when this build has
    !> one and a GPU is visible, else the CPU; 'cpu'; 'gpu' (refused when there is none)
    integer, parameter :: DEVICE_AUTO = 1, DEVICE_CPU = 2, DEVICE_GPU = 3
    character(len=*), parameter :: device_names(3) = [character(len=4) :: 'auto', 'cpu', 'gpu']

    type :: solver_options_t
        integer :: method = SOLVER_AUTO         !! SOLVER_* id
        integer :: device = DEVICE_AUTO         !! DEVICE_* id
        real(dp) :: tolerance = 1.0e-10_dp      !! target of the residual [-]
        integer :: max_iterations = 20000       !! iteration cap
        integer :: refresh_every = 200          !! recompute K p exactly this often (pk)
        !> Anderson mixing depth (dr, pdr); 0 switches it off, negative: the method's default
        !> (veslide_solver: dr 5, pdr 0)
        integer :: anderson_memory = -1
        integer :: balance_every = 50           !! step-size balancing interval (dr; docs/solver-scaling.md)
        real(dp) :: step = 0.0_dp               !! initial dimensionless step (dr); 0: automatic
        real(dp) :: balance_ratio = 10.0_dp     !! imbalance of the residuals that changes the step (dr)
        real(dp) :: balance_factor = 3.0_dp     !! factor the step changes by (dr)
        !> told about the solve every `progress_every_s` seconds (none: silent)
        procedure(solver_progress_callback), pointer, nopass :: progress => null()
        real(dp) :: progress_every_s = 5.0_dp
        !> on the device, pdr's lean layout (veslide_solver_pdr) even where the device has room for
        !> the exact one (tests; not an input)
        logical :: device_lean = .false.
    end type solver_options_t

    !> What a solver's progress callback is told
    type :: solver_progress_t
        character(len=4) :: method = ''         !! the method running
        integer :: iterations = 0               !! iterations so far (pdr: inner bccg iterations)
        real(dp) :: residual = huge(1.0_dp)     !! the method's current residual measure [-]
        real(dp) :: tolerance = 0.0_dp          !! its target [-]
        integer :: operator_applications = 0    !! FFT pairs so far
        real(dp) :: seconds = 0.0_dp            !! since the solve began [s]
    end type solver_progress_t

    abstract interface
        subroutine solver_progress_callback(info)
            import :: solver_progress_t
            type(solver_progress_t), intent(in) :: info
        end subroutine solver_progress_callback
    end interface

    !> A solver's clock for its progress reports: `tick` each iteration, it calls the options'
    !> callback when `progress_every_s` seconds have passed since the last report, and lets the
    !> governor set the threads of the next iteration
    type :: progress_ticker_t
        procedure(solver_progress_callback), pointer, nopass :: callback => null()
        character(len=4) :: method = ''
        real(dp) :: every = 5.0_dp, tolerance = 0.0_dp, t0 = 0.0_dp, last = 0.0_dp
        type(thread_governor_t) :: governor
    contains
        procedure :: start => ticker_start
        procedure :: tick => ticker_tick
    end type progress_ticker_t

contains

    !> SOLVER_* id from a method name; 0 when unknown
    pure integer function solver_method_id(name) result(id)
        character(len=*), intent(in) :: name
        id = name_index(name, solver_method_names)
    end function solver_method_id

    !> DEVICE_* id from a name ('auto', 'cpu', 'gpu'); 0 when unknown
    pure integer function device_choice_id(name) result(id)
        character(len=*), intent(in) :: name
        id = name_index(name, device_names)
    end function device_choice_id

    !> The line a program prints for a progress report
    function progress_line(info) result(line)
        type(solver_progress_t), intent(in) :: info
        character(len=:), allocatable :: line
        character(len=160) :: buf
        write (buf, '("solver ",a,": iteration ",i0,", residual ",es9.2," (target ",es8.1,"), ",i0, &
            &" FFT pairs, ",f0.1," s")') trim(info%method), info%iterations, info%residual, info%tolerance, &
            info%operator_applications, info%seconds
        line = trim(buf)
    end function progress_line

    !> Start the clock of a solve by `method` with the options' callback and interval
    subroutine ticker_start(self, opts, method)
        class(progress_ticker_t), intent(out) :: self
        type(solver_options_t), intent(in) :: opts
        character(len=*), intent(in) :: method
        self%callback => opts%progress
        self%method = method; self%every = opts%progress_every_s; self%tolerance = opts%tolerance
        call self%governor%start()
        if (associated(self%callback)) then
            self%t0 = wall_seconds(); self%last = self%t0
        end if
    end subroutine ticker_start

    !> One iteration done: the threads of the next, and a report if the interval has passed
    subroutine ticker_tick(self, iterations, residual, operator_applications)
        class(progress_ticker_t), intent(inout) :: self
        integer, intent(in) :: iterations, operator_applications
        real(dp), intent(in) :: residual
        real(dp) :: t
        call self%governor%tick()
        if (.not. associated(self%callback)) return
        t = wall_seconds()
        if (t - self%last < self%every) return
        self%last = t
        call self%callback(solver_progress_t(self%method, iterations, residual, self%tolerance, &
                                             operator_applications, t - self%t0))
    end subroutine ticker_tick

end module veslide_solver_options
