!> Solving a contact problem: the method chosen for the operator, the start, the report.
!>  - 'pk': Polonsky-Keer constrained conjugate gradient (symmetric operators: the elastic case),
!>    `veslide_solver_pk`;
!>  - 'dr': Douglas-Rachford splitting with Anderson acceleration, convergent without symmetry
!>    (the viscoelastic case), `veslide_solver_dr`;
!>  - 'auto': pk when the kernel is symmetric, else dr.
!> A new solver is one module with the signature of the two above and one `case` here.
module veslide_solver
    use veslide_kinds, only: dp
    use veslide_error, only: error_t, fatal_error
    use veslide_fftw, only: fft2d_t
    use veslide_contact, only: contact_problem_t, contact_state_t
    use veslide_solver_options, only: solver_options_t, SOLVER_AUTO, SOLVER_PK, SOLVER_DR
    use veslide_solver_pk, only: polonsky_keer
    use veslide_solver_dr, only: douglas_rachford
    implicit none
    private
    public :: solve_contact

contains

    !> Solve `problem`; `p_init` (with its gap `g_init` for dr) warm-starts from a previous solution
    subroutine solve_contact(problem, fft, opts, state, error, p_init, g_init)
        type(contact_problem_t), intent(in) :: problem
        type(fft2d_t), intent(inout) :: fft
        type(solver_options_t), intent(in) :: opts
        type(contact_state_t), intent(out) :: state
        type(error_t), allocatable, intent(out) :: error
        real(dp), intent(in), optional :: p_init(:, :)
        !> gap that goes with p_init [m] (the splitting method starts from both)
        real(dp), intent(in), optional :: g_init(:, :)
        integer :: method

        if (problem%kernel%grid%nx /= fft%nx .or. problem%kernel%grid%ny /= fft%ny) then
            call fatal_error(error, "veslide:solver:solve_contact: problem and FFT grids differ"); return
        end if
        method = opts%method
        if (method == SOLVER_AUTO) method = merge(SOLVER_PK, SOLVER_DR, problem%kernel%symmetric)
        call problem%start(state, p_init)
        select case (method)
        case (SOLVER_PK)
            if (.not. problem%kernel%symmetric) then
                call fatal_error(error, "veslide:solver:solve_contact: method 'pk' needs a symmetric (elastic)"// &
                    " kernel; use 'dr' or 'auto'"); return
            end if
            call polonsky_keer(problem, fft, opts, state)
        case (SOLVER_DR)
            if (present(p_init) .and. present(g_init)) then
                call douglas_rachford(problem, fft, opts, state, gap0=g_init)
            else
                call douglas_rachford(problem, fft, opts, state)
            end if
        case default
            call fatal_error(error, "veslide:solver:solve_contact: unknown method"); return
        end select
    end subroutine solve_contact

end module veslide_solver
