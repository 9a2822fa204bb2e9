!> Shared set-up for the tests: a problem or a solve in a few lines, unique file names, text files
module test_support
    use veslide_kinds, only: dp
    use veslide_error, only: error_t, fatal_error
    use veslide_grid, only: grid_t, new_grid
    use veslide_fftw, only: fft2d_t
    use veslide_material, only: material_t, new_elastic
    use veslide_kernel, only: kernel_t, new_kernel, KERNEL_SPECTRAL
    use veslide_contact, only: contact_problem_t, contact_state_t, new_contact_problem
    use veslide_solver_options, only: solver_options_t, solver_method_id, device_choice_id
    use veslide_solver, only: solve_contact
    use veslide_output, only: process_id
    implicit none
    private
    public :: solve_case, case_problem, unique_name, write_text, square_grid, remove

contains

    !> The grid of an (lx, ly) cell sampled like h
    function square_grid(h, lx, ly) result(grid)
        real(dp), intent(in) :: h(:, :), lx, ly
        type(grid_t) :: grid
        type(error_t), allocatable :: error
        call new_grid(grid, size(h, 1), size(h, 2), lx, ly, error)
    end function square_grid

    !> Solve h on an (lx, ly) cell against material `mat` (default: elastic with E* = estar, nu = 0)
    subroutine solve_case(h, lx, ly, p_mean, state, error, estar, mat, velocity, variant, tol, method, p_init, kernel, &
                          device, anderson_memory)
        real(dp), intent(in) :: h(:, :), lx, ly, p_mean
        type(contact_state_t), intent(out) :: state
        type(error_t), allocatable, intent(out) :: error
        real(dp), intent(in), optional :: estar, velocity(2), tol, p_init(:, :)
        type(material_t), intent(in), optional :: mat
        integer, intent(in), optional :: variant
        character(len=*), intent(in), optional :: method
        type(kernel_t), intent(out), optional :: kernel
        !> where to solve: 'auto' (default), 'cpu' or 'gpu'
        character(len=*), intent(in), optional :: device
        !> the options' Anderson memory (default: each method's own)
        integer, intent(in), optional :: anderson_memory
        type(material_t) :: m
        type(kernel_t) :: k
        type(fft2d_t) :: fft
        type(contact_problem_t) :: problem
        type(solver_options_t) :: opts
        real(dp) :: v(2)
        if (present(mat)) then
            m = mat
        else
            call new_elastic(m, merge(estar, 1.0e6_dp, present(estar)), 0.0_dp, error)
            if (allocated(error)) return
        end if
        v = 0.0_dp; if (present(velocity)) v = velocity
        call case_problem(h, lx, ly, p_mean, m, v, problem, error, variant=variant, kernel=k, fft=fft)
        if (allocated(error)) return
        opts%tolerance = 1.0e-12_dp; if (present(tol)) opts%tolerance = tol
        if (present(method)) opts%method = solver_method_id(method)
        if (present(device)) opts%device = device_choice_id(device)
        if (present(anderson_memory)) opts%anderson_memory = anderson_memory
        call solve_contact(problem, fft, opts, state, error, p_init=p_init)
        if (allocated(error)) return
        if (.not. state%converged) call fatal_error(error, "solver did not converge")
        if (present(kernel)) kernel = k
    end subroutine solve_case

    !> The problem of heights h on an (lx, ly) cell against `mat` moving at `velocity`, pressed to
    !> p_mean; when asked for, its kernel (`variant`, spectral when absent) and the transforms
    subroutine case_problem(h, lx, ly, p_mean, mat, velocity, problem, error, variant, kernel, fft)
        real(dp), intent(in) :: h(:, :), lx, ly, p_mean, velocity(2)
        type(material_t), intent(in) :: mat
        type(contact_problem_t), intent(out) :: problem
        type(error_t), allocatable, intent(out) :: error
        integer, intent(in), optional :: variant
        type(kernel_t), intent(out), optional :: kernel
        type(fft2d_t), intent(out), optional :: fft
        type(kernel_t) :: k
        integer :: var
        var = KERNEL_SPECTRAL; if (present(variant)) var = variant
        if (present(fft)) then
            call fft%init(size(h, 1), size(h, 2), error, planner='estimate'); if (allocated(error)) return
        end if
        call new_kernel(k, square_grid(h, lx, ly), mat, velocity, var, error); if (allocated(error)) return
        call new_contact_problem(problem, k, h, p_mean, error); if (allocated(error)) return
        if (present(kernel)) kernel = k
    end subroutine case_problem

    !> A file name unique to this process and tag, in the system's temporary directory
    function unique_name(tag) result(name)
        character(len=*), intent(in) :: tag
        character(len=:), allocatable :: name
        character(len=16) :: pid
        write (pid, '(i0)') process_id()
        name = '/tmp/veslide-test-'//trim(pid)//'-'//tag
    end function unique_name

    !> Delete `path` when it is there (a test's file in the temporary directory)
    subroutine remove(path)
        character(len=*), intent(in) :: path
        integer :: u, stat
        open (newunit=u, file=path, iostat=stat); if (stat == 0) close (u, status='delete')
    end subroutine remove

    subroutine write_text(path, text)
        character(len=*), intent(in) :: path, text
        integer :: u
        open (newunit=u, file=path, status='replace', action='write')
        write (u, '(a)') text
        close (u)
    end subroutine write_text

end module test_support
