!> Solving a contact problem: the method chosen for the operator, the start, the report.
!>  - 'pk': Polonsky-Keer constrained conjugate gradient (symmetric operators: the elastic case),
!>    `veslide_solver_pk`;
!>  - 'dr': Douglas-Rachford splitting with Anderson acceleration, convergent without symmetry
!>    (the viscoelastic case), `veslide_solver_dr`;
!>  - 'bccg': bound-constrained conjugate gradient with the FFT preconditioner (symmetric
!>    operators), `veslide_solver_bccg`: its iteration count barely grows with the grid;
!>  - 'pdr': Douglas-Rachford in the metric of |K| with BCCG for the metric projection
!>    (any operator), `veslide_solver_pdr`: its iteration count barely grows with the grid;
!>  - 'auto': bccg when the kernel is symmetric; else pdr on grids of at least `pdr_min_cells`
!>    cells whose operator is not too anisotropic (`modulus_spread` at most `pdr_max_spread`),
!>    and dr otherwise (docs/solver-scaling.md: the measurements behind the two thresholds).
!> A new solver is one module with the signature of the ones above and one `case` here.
module veslide_solver
    use veslide_kinds, only: dp
    use veslide_error, only: error_t, fatal_error
    use veslide_fftw, only: fft2d_t
    use veslide_contact, only: contact_problem_t, contact_state_t
    use veslide_solver_options, only: solver_options_t, SOLVER_AUTO, SOLVER_PK, SOLVER_DR, SOLVER_BCCG, SOLVER_PDR
    use veslide_solver_pk, only: polonsky_keer
    use veslide_solver_dr, only: douglas_rachford
    use veslide_solver_bccg, only: bccg_solve
    use veslide_solver_pdr, only: preconditioned_douglas_rachford
    use veslide_threads, only: restore_threads
    implicit none
    private
    public :: solve_contact, auto_method, pdr_min_cells, default_anderson_memory

    !> 'auto' takes pdr for a non-symmetric kernel from this many cells up (256^2: there pdr took
    !> 0.56 of dr's time over the 16 hard cases it is chosen for, though more on contacts near
    !> full; docs/solver-scaling.md)...
    integer, parameter :: pdr_min_cells = 256*256
    !> ...when the operator's anisotropy is at most this (pdr's inner problems slow down for
    !> strongly anisotropic operators: Einf/E0 of 100 and more in motion)
    real(dp), parameter :: pdr_max_spread = 20.0_dp
    !> Anderson memory when the options leave it to the method (anderson_memory < 0): dr mixes 5
    !> steps; pdr takes the over-relaxed plain step, which spends as many FFT pairs as mixing on
    !> the hard cases (within 1 %) and fewer on the paper scene, for 52 bytes per cell less
    !> (docs/solver-scaling.md)
    integer, parameter :: dr_anderson_memory = 5, pdr_anderson_memory = 0

contains

    !> Solve `problem`; `p_init` (with its gap `g_init` for dr) warm-starts from a previous solution.
    !> `problem` is returned as it came (a solver may borrow its kernel's multiplier while it runs).
    subroutine solve_contact(problem, fft, opts, state, error, p_init, g_init)
        type(contact_problem_t), intent(inout) :: problem
        type(fft2d_t), intent(inout) :: fft
        type(solver_options_t), intent(in) :: opts
        type(contact_state_t), intent(out) :: state
        type(error_t), allocatable, intent(out) :: error
        real(dp), intent(in), optional :: p_init(:, :)
        !> gap that goes with p_init [m] (the splitting method starts from both)
        real(dp), intent(in), optional :: g_init(:, :)
        integer :: method
        type(solver_options_t) :: o

        if (problem%kernel%grid%nx /= fft%nx .or. problem%kernel%grid%ny /= fft%ny) then
            call fatal_error(error, "veslide:solver:solve_contact: problem and FFT grids differ"); return
        end if
        method = opts%method
        if (method == SOLVER_AUTO) method = auto_method(problem)
        o = opts
        o%anderson_memory = default_anderson_memory(method, opts%anderson_memory)
        call problem%start(state, p_init)
        select case (method)
        case (SOLVER_PK)
            if (.not. problem%kernel%symmetric) then
                call fatal_error(error, "veslide:solver:solve_contact: method 'pk' needs a symmetric (elastic)"// &
                    " kernel; use 'dr' or 'auto'"); return
            end if
            call polonsky_keer(problem, fft, o, state)
        case (SOLVER_BCCG)
            if (.not. problem%kernel%symmetric) then
                call fatal_error(error, "veslide:solver:solve_contact: method 'bccg' needs a symmetric (elastic)"// &
                    " kernel; use 'pdr', 'dr' or 'auto'"); return
            end if
            call bccg_solve(problem, fft, o, state)
        case (SOLVER_DR)
            if (present(p_init) .and. present(g_init)) then
                call douglas_rachford(problem, fft, o, state, gap0=g_init)
            else
                call douglas_rachford(problem, fft, o, state)
            end if
        case (SOLVER_PDR)
            if (present(p_init) .and. present(g_init)) then
                call preconditioned_douglas_rachford(problem, fft, o, state, gap0=g_init)
            else
                call preconditioned_douglas_rachford(problem, fft, o, state, cold=.not. present(p_init))
            end if
        case default
            call fatal_error(error, "veslide:solver:solve_contact: unknown method"); return
        end select
        call restore_threads()     ! the thread governor may have lowered them (veslide_threads)
    end subroutine solve_contact

    !> The Anderson memory `method` (SOLVER_*) runs with when the options ask for `memory`
    !> (negative: the method's default)
    pure integer function default_anderson_memory(method, memory) result(m)
        integer, intent(in) :: method, memory
        m = memory
        if (m >= 0) return
        select case (method)
        case (SOLVER_PDR)
            m = pdr_anderson_memory
        case default
            m = dr_anderson_memory
        end select
    end function default_anderson_memory

    !> The method 'auto' takes for a problem (see the module's header)
    integer function auto_method(problem) result(method)
        type(contact_problem_t), intent(in) :: problem
        if (problem%kernel%symmetric) then
            method = SOLVER_BCCG
        else if (problem%kernel%grid%cells() >= pdr_min_cells .and. &
                 problem%kernel%modulus_spread() <= pdr_max_spread) then
            method = SOLVER_PDR
        else
            method = SOLVER_DR
        end if
    end function auto_method

end module veslide_solver
