!> &solver: the method, its tolerance and knobs, the kernel variant, the FFT planner
module veslide_config_solver
    use veslide_kinds, only: dp
    use veslide_error, only: error_t
    use veslide_strings, only: str
    use veslide_config_common, only: namelist_status, require, choices_text, is_one_of
    use veslide_solver_options, only: solver_method_names
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
        integer :: threads = 1                           !! threads per FFT
        integer :: anderson_memory = 5, balance_every = 100   ! 100: docs/solver-scaling.md
        real(dp) :: balance_ratio = 10.0_dp, balance_factor = 3.0_dp
    end type solver_config_t

contains

    !> Read &solver from the open namelist file `u` (absent: defaults) and check it
    subroutine read_solver_config(self, u, path, error)
        type(solver_config_t), intent(out) :: self
        integer, intent(in) :: u
        character(len=*), intent(in) :: path
        type(error_t), allocatable, intent(out) :: error
        character(len=16) :: method, fft_planner
        character(len=24) :: kernel
        real(dp) :: tolerance, alias_tol, balance_ratio, balance_factor
        integer :: max_iterations, alias_max, threads, anderson_memory, balance_every, stat
        character(len=512) :: msg
        namelist /solver/ method, tolerance, max_iterations, kernel, alias_tol, alias_max, fft_planner, threads, &
            anderson_memory, balance_every, balance_ratio, balance_factor
        method = 'auto'; tolerance = self%tolerance; max_iterations = self%max_iterations; kernel = 'spectral'
        alias_tol = self%alias_tol; alias_max = self%alias_max; fft_planner = 'measure'; threads = self%threads
        anderson_memory = self%anderson_memory; balance_every = self%balance_every
        balance_ratio = self%balance_ratio; balance_factor = self%balance_factor
        rewind (u); read (u, nml=solver, iostat=stat, iomsg=msg)
        call namelist_status(stat, msg, path, 'solver', error); if (allocated(error)) return
        self%method = trim(method); self%tolerance = tolerance; self%max_iterations = max_iterations
        self%kernel = trim(kernel); self%alias_tol = alias_tol; self%alias_max = alias_max
        self%fft_planner = trim(fft_planner); self%threads = threads
        self%anderson_memory = anderson_memory; self%balance_every = balance_every
        self%balance_ratio = balance_ratio; self%balance_factor = balance_factor

        call require(error, is_one_of(self%method, solver_method_names), path, 'solver', 'method', &
                     "'"//self%method//"'", choices_text(solver_method_names))
        call require(error, tolerance >= 1.0e-15_dp .and. tolerance <= 1.0e-2_dp, path, 'solver', 'tolerance', &
                     str(tolerance), "1e-15 to 1e-2")
        call require(error, max_iterations >= 1 .and. max_iterations <= 10000000, path, 'solver', 'max_iterations', &
                     str(max_iterations), "1 to 10000000")
        call require(error, is_one_of(self%kernel, kernel_names), path, 'solver', 'kernel', "'"//self%kernel//"'", &
                     choices_text(kernel_names))
        call require(error, alias_tol > 0.0_dp .and. alias_tol <= 0.1_dp, path, 'solver', 'alias_tol', &
                     str(alias_tol), "0 < alias_tol <= 0.1")
        call require(error, alias_max >= 2 .and. alias_max <= 1024, path, 'solver', 'alias_max', str(alias_max), &
                     "2 to 1024")
        call require(error, is_one_of(self%fft_planner, fft_planner_names), path, 'solver', 'fft_planner', &
                     "'"//self%fft_planner//"'", choices_text(fft_planner_names))
        call require(error, anderson_memory >= 0 .and. anderson_memory <= 50, path, 'solver', 'anderson_memory', &
                     str(anderson_memory), "0 (off) to 50")
        call require(error, balance_every >= 1 .and. balance_every <= 100000, path, 'solver', 'balance_every', &
                     str(balance_every), "1 to 100000")
        call require(error, balance_ratio >= 1.0_dp .and. balance_ratio <= 1.0e6_dp, path, 'solver', &
                     'balance_ratio', str(balance_ratio), "1 to 1e6")
        call require(error, balance_factor > 1.0_dp .and. balance_factor <= 100.0_dp, path, 'solver', &
                     'balance_factor', str(balance_factor), "> 1 and <= 100")
        call require(error, threads >= 1 .and. threads <= 1024, path, 'solver', 'threads', str(threads), "1 to 1024")
    end subroutine read_solver_config

end module veslide_config_solver
