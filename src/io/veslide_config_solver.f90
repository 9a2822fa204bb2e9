!> &solver: the method, its tolerance and knobs, the kernel variant, the FFT planner, the device
module veslide_config_solver
    use veslide_kinds, only: dp
    use veslide_error, only: error_t
    use veslide_strings, only: str
    use veslide_config_common, only: group_text_t, diagnose_read, read_failed, split_lines, require, choices_text, is_one_of, &
                                     finite_in, check_text_length, max_text
    use veslide_solver_options, only: solver_method_names, device_names
    use veslide_kernel, only: kernel_names
    use veslide_fftw, only: fft_planner_names
    implicit none
    private
    public :: solver_config_t, read_solver_config

    type :: solver_config_t
        character(len=:), allocatable :: method          !! one of solver_method_names
        real(dp) :: tolerance = 1.0e-10_dp               !! target of the residual
        integer :: max_iterations = 20000
        character(len=:), allocatable :: kernel          !! one of kernel_names
        real(dp) :: alias_tol = 1.0e-6_dp                !! alias sums: relative tolerance
        integer :: alias_max = 64                        !! alias sums: largest zone index
        character(len=:), allocatable :: fft_planner     !! one of fft_planner_names
        integer :: threads = 0                           !! OpenMP threads of the run (0: OMP_NUM_THREADS)
        !> Anderson memory; -1: the method's own (dr 5, pdr 0: its over-relaxed plain step)
        integer :: anderson_memory = -1
        integer :: balance_every = 50                    ! docs/solver-scaling.md: why not 100
        real(dp) :: balance_ratio = 10.0_dp, balance_factor = 3.0_dp
        character(len=:), allocatable :: device          !! one of device_names: where the solve runs
    end type solver_config_t

    character(len=*), parameter :: names(13) = [character(len=15) :: 'method', 'tolerance', 'max_iterations', &
        'kernel', 'alias_tol', 'alias_max', 'fft_planner', 'threads', 'anderson_memory', 'balance_every', &
        'balance_ratio', 'balance_factor', 'device']
    character(len=*), parameter :: kinds(13) = [character(len=24) :: "a quoted text ('auto')", 'a real number', &
        'an integer', "a quoted text ('spectral')", 'a real number', 'an integer', "a quoted text ('measure')", &
        'an integer', 'an integer', 'an integer', 'a real number', 'a real number', "a quoted text ('auto')"]
    !> The smallest tolerance double precision reaches: K p is computed to about 1e-15 relative,
    !> and the residual's measures sum over the grid
    real(dp), parameter :: min_tolerance = 1.0e-13_dp

contains

    !> Read &solver from its text (absent: defaults) and check it
    subroutine read_solver_config(self, g, path, error)
        type(solver_config_t), intent(out) :: self
        type(group_text_t), intent(in) :: g
        character(len=*), intent(in) :: path
        type(error_t), allocatable, intent(out) :: error
        character(len=max_text + 1) :: method, fft_planner, device
        character(len=max_text + 1) :: kernel
        real(dp) :: tolerance, alias_tol, balance_ratio, balance_factor
        integer :: max_iterations, alias_max, threads, anderson_memory, balance_every, stat
        character(len=512) :: msg
        character(len=:), allocatable :: lines(:)
        namelist /solver/ method, tolerance, max_iterations, kernel, alias_tol, alias_max, fft_planner, threads, &
            anderson_memory, balance_every, balance_ratio, balance_factor, device
        method = 'auto'; device = 'auto'; tolerance = self%tolerance; max_iterations = self%max_iterations; kernel = 'spectral'
        alias_tol = self%alias_tol; alias_max = self%alias_max; fft_planner = 'measure'; threads = self%threads
        anderson_memory = self%anderson_memory; balance_every = self%balance_every
        balance_ratio = self%balance_ratio; balance_factor = self%balance_factor
        call split_lines(g%text, lines)
        read (lines, nml=solver, iostat=stat, iomsg=msg)
        if (read_failed(stat)) then
            call diagnose_read(stat, msg, path, 'solver', g%body, names, kinds, try, error); return
        end if
        call check_text_length(error, method, path, 'solver', 'method', g%body)
        call check_text_length(error, kernel, path, 'solver', 'kernel', g%body)
        call check_text_length(error, fft_planner, path, 'solver', 'fft_planner', g%body)
        call check_text_length(error, device, path, 'solver', 'device', g%body); if (allocated(error)) return
        self%method = trim(method); self%tolerance = tolerance; self%max_iterations = max_iterations
        self%kernel = trim(kernel); self%alias_tol = alias_tol; self%alias_max = alias_max
        self%fft_planner = trim(fft_planner); self%threads = threads
        self%anderson_memory = anderson_memory; self%balance_every = balance_every
        self%balance_ratio = balance_ratio; self%balance_factor = balance_factor
        self%device = trim(device)

        call require(error, is_one_of(self%method, solver_method_names), path, 'solver', 'method', &
                     "'"//self%method//"'", choices_text(solver_method_names))
        call require(error, finite_in(tolerance, min_tolerance, 1.0e-2_dp), path, 'solver', 'tolerance', &
                     str(tolerance), "1e-13 to 1e-2 (smaller residuals are below the round-off of double precision)")
        call require(error, max_iterations >= 1 .and. max_iterations <= 10000000, path, 'solver', 'max_iterations', &
                     str(max_iterations), "1 to 10000000")
        call require(error, is_one_of(self%kernel, kernel_names), path, 'solver', 'kernel', "'"//self%kernel//"'", &
                     choices_text(kernel_names))
        call require(error, finite_in(alias_tol, 0.0_dp, 0.1_dp, open_low=.true.), path, 'solver', 'alias_tol', &
                     str(alias_tol), "0 < alias_tol <= 0.1")
        call require(error, alias_max >= 2 .and. alias_max <= 1024, path, 'solver', 'alias_max', str(alias_max), &
                     "2 to 1024")
        call require(error, is_one_of(self%fft_planner, fft_planner_names), path, 'solver', 'fft_planner', &
                     "'"//self%fft_planner//"'", choices_text(fft_planner_names))
        call require(error, anderson_memory >= -1 .and. anderson_memory <= 50, path, 'solver', 'anderson_memory', &
                     str(anderson_memory), "-1 (the method's default), 0 (off) to 50")
        call require(error, balance_every >= 1 .and. balance_every <= 100000, path, 'solver', 'balance_every', &
                     str(balance_every), "1 to 100000")
        call require(error, finite_in(balance_ratio, 1.0_dp, 1.0e6_dp), path, 'solver', &
                     'balance_ratio', str(balance_ratio), "1 to 1e6")
        call require(error, finite_in(balance_factor, 1.0_dp, 100.0_dp, open_low=.true.), path, 'solver', &
                     'balance_factor', str(balance_factor), "> 1 and <= 100")
        call require(error, threads >= 0 .and. threads <= 1024, path, 'solver', 'threads', str(threads), &
                     "0 (as OMP_NUM_THREADS) to 1024")
        call require(error, is_one_of(self%device, device_names), path, 'solver', 'device', "'"//self%device//"'", &
                     choices_text(device_names))
    contains
        subroutine try(lines, stat, msg)
            character(len=*), intent(in) :: lines(:)
            integer, intent(out) :: stat
            character(len=*), intent(out) :: msg
            character(len=max_text + 1) :: method, fft_planner, device
            character(len=max_text + 1) :: kernel
            real(dp) :: tolerance, alias_tol, balance_ratio, balance_factor
            integer :: max_iterations, alias_max, threads, anderson_memory, balance_every
            namelist /solver/ method, tolerance, max_iterations, kernel, alias_tol, alias_max, fft_planner, threads, &
                anderson_memory, balance_every, balance_ratio, balance_factor, device
            read (lines, nml=solver, iostat=stat, iomsg=msg)
        end subroutine try
    end subroutine read_solver_config

end module veslide_config_solver
