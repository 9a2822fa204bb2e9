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
!>    and dr otherwise (docs/solver-scaling.md: the measurements behind the two thresholds);
!>    of these the first the solver table says takes the case (its operator, its contact law).
!> Where: on the CPU, or on the device (a GPU: `&solver device`, `solve_on_device`), the same
!> control flow on arrays held there (`contact_fields_t`); pk runs on the CPU only.
!> What each method takes (a symmetric operator or any, which contact laws, the device) is the
!> solver table's (veslide_solver_table): the refusals here are its, worded as at the input.
!> A new solver is one module with the signature of the ones above, one `case` here and its row
!> in the table.
module veslide_solver
    use veslide_kinds, only: dp
    use veslide_error, only: error_t, fatal_error
    use veslide_fftw, only: fft2d_t
    use veslide_contact, only: contact_problem_t, contact_state_t, contact_fields_t
    use veslide_solver_options, only: solver_options_t, SOLVER_AUTO, SOLVER_PK, SOLVER_DR, SOLVER_BCCG, SOLVER_PDR, &
                                      SOLVER_GCG, &
                                      DEVICE_CPU, DEVICE_GPU
    use veslide_solver_table, only: solver_info_t, solver_info, method_takes, method_refusal, device_refusal, &
                                    memory_refusal, runs_on_device
    use veslide_anderson_passes, only: device_max_memory
    use veslide_device, only: device_enabled, device_count, device_emulated, device_check
    use veslide_contact_law, only: LAW_HARD_WALL
    use veslide_solver_pk, only: polonsky_keer
    use veslide_solver_dr, only: douglas_rachford
    use veslide_solver_bccg, only: bccg_solve
    use veslide_solver_pdr, only: preconditioned_douglas_rachford
    use veslide_solver_gcg, only: gap_conjugate_gradients
    use veslide_threads, only: restore_threads
    implicit none
    private
    public :: solve_contact, auto_method, auto_rule, planned_methods, pdr_min_cells, pdr_max_spread, &
              default_anderson_memory, solve_on_device, gpu_visible, check_device_choice, auto_takes_device, &
              method_check

    !> 'auto' takes pdr for a non-symmetric kernel from this many cells up (256^2: there pdr took
    !> 0.56 of dr's time over the 16 hard cases it is chosen for, though more on contacts near
    !> full; docs/solver-scaling.md)...
    integer, parameter :: pdr_min_cells = 256*256
    !> ...when the operator's anisotropy is at most this (pdr's inner problems slow down for
    !> strongly anisotropic operators: Einf/E0 of 100 and more in motion)
    real(dp), parameter :: pdr_max_spread = 20.0_dp

contains

    !> Solve `problem`; `p_init` (with its gap `g_init` for dr) warm-starts from a previous solution.
    !> The solve runs where `opts%device` says (solve_on_device): on the device the heights, the
    !> kernel's multiplier and the start go in, p, u and g come out, nothing else crosses. Every
    !> method ends with the one verdict on its result: u = K p computed afresh and the residual
    !> measured (`problem%confirm`), converged exactly when that residual is <= the tolerance.
    subroutine solve_contact(problem, fft, opts, state, error, p_init, g_init, keep, same_heights)
        type(contact_problem_t), intent(inout), target :: problem
        type(fft2d_t), intent(inout), target :: fft
        type(solver_options_t), intent(in) :: opts
        type(contact_state_t), intent(out), target :: state
        type(error_t), allocatable, intent(out) :: error
        real(dp), intent(in), optional :: p_init(:, :)
        !> gap that goes with p_init [m] (the splitting method starts from both)
        real(dp), intent(in), optional :: g_init(:, :)
        !> a study's fields, kept on the device from one case to the next of its chain: where they
        !> hold the previous case's p and g, and p_init and g_init are those (downloaded), the
        !> start is formed there and neither goes up (nor the heights, when `same_heights`); left
        !> holding this case's (freed where the case is not solved on the device)
        type(contact_fields_t), intent(inout), optional, target :: keep
        logical, intent(in), optional :: same_heights
        integer :: method
        type(solver_options_t) :: o
        type(contact_fields_t), target :: own
        type(contact_fields_t), pointer :: f
        real(dp) :: factor
        logical :: device

        if (problem%kernel%grid%nx /= fft%nx .or. problem%kernel%grid%ny /= fft%ny) then
            call fatal_error(error, "veslide:solver:solve_contact: problem and FFT grids differ"); return
        end if
        ! what the method takes (the solver table), then where it runs
        call method_check(opts%method, problem%kernel%symmetric, problem%law%kind, error)
        if (allocated(error)) return
        method = opts%method
        if (method == SOLVER_AUTO) method = auto_method(problem)
        if (problem%approach_control .and. method /= SOLVER_GCG) then
            call fatal_error(error, "veslide:solver: approach control is taken by 'gcg' alone (an adhesive law)"); return
        end if
        o = opts
        o%anderson_memory = default_anderson_memory(method, opts%anderson_memory)
        call solve_on_device(opts%device, problem, device, error, method, o)
        if (allocated(error)) then
            if (present(keep)) call keep%finish()
            return
        end if
        call problem%start(state, p_init, factor)
        if (method == SOLVER_PK) call polonsky_keer(problem, fft, o, state)
        if (present(keep)) then
            f => keep
            if (present(p_init) .and. present(g_init)) then
                call problem%fields(f, fft, state, device, error, kept_start=factor, same_heights=same_heights)
            else
                call problem%fields(f, fft, state, device, error)
            end if
        else
            f => own
            call problem%fields(f, fft, state, device, error)
        end if
        if (allocated(error)) return
        select case (method)
        case (SOLVER_BCCG)
            call bccg_solve(problem, f, o, state)
        case (SOLVER_DR)
            if (present(p_init) .and. present(g_init)) then
                call douglas_rachford(problem, f, o, state, gap0=g_init)
            else
                call douglas_rachford(problem, f, o, state)
            end if
        case (SOLVER_GCG)
            if (present(g_init)) then
                call gap_conjugate_gradients(problem, f, o, state, gap0=g_init)
            else
                call gap_conjugate_gradients(problem, f, o, state)
            end if
        case (SOLVER_PDR)
            if (present(p_init) .and. present(g_init)) then
                call preconditioned_douglas_rachford(problem, f, o, state, gap0=g_init)
            else
                call preconditioned_douglas_rachford(problem, f, o, state, cold=.not. present(p_init))
            end if
        end select
        ! the verdict, on the number reported
        call problem%confirm(f, state, opts%tolerance)
        state%p_scale_pa = problem%p_scale_pa
        call device_check(error, "veslide:solver:solve_contact: "//state%method//" on the device")
        call f%finish(state, keep=present(keep) .and. .not. allocated(error))
        state%device = merge('gpu', 'cpu', device)
        call restore_threads()     ! the thread governor may have lowered them (veslide_threads)
    end subroutine solve_contact

    !> Where a solve of `problem` runs for the choice `choice` (DEVICE_*): on the device
    !> (`device` true) or the CPU. 'gpu' without a usable GPU, on a distributed grid, or for what
    !> the device does not run (`method` with the options `o`, when given) is refused; 'auto'
    !> takes the CPU in those cases.
    subroutine solve_on_device(choice, problem, device, error, method, o)
        integer, intent(in) :: choice
        type(contact_problem_t), intent(in) :: problem
        logical, intent(out) :: device
        type(error_t), allocatable, intent(out) :: error
        integer, intent(in), optional :: method
        type(solver_options_t), intent(in), optional :: o
        device = .false.
        select case (choice)
        case (DEVICE_CPU)
            return
        case (DEVICE_GPU)
            call check_device_choice(choice, error); if (allocated(error)) return
            if (problem%kernel%grid%is_distributed()) then
                call fatal_error(error, "veslide:solver: &solver device = 'gpu' on a grid distributed over processes"// &
                    " is not available (an MPI study gives each rank its own GPU); use 'cpu'"); return
            end if
            if (present(method) .and. present(o)) then
                call device_limits(method, o, problem%kernel%symmetric, problem%law%kind, error)
                if (allocated(error)) return
            end if
            device = .true.
        case default
            if (present(method) .and. present(o)) then
                device = auto_takes_device(method, o%anderson_memory, problem%kernel%grid%is_distributed())
            else
                device = auto_takes_device(SOLVER_AUTO, -1, problem%kernel%grid%is_distributed())
            end if
        end select
    end subroutine solve_on_device

    !> Does 'auto' solve on the device: a GPU is visible, the grid is not shared by processes, and
    !> the device runs `method` (the solver table; SOLVER_AUTO: one the rule picks, all of which it
    !> runs) with Anderson memory `memory` (negative: the method's own). The one rule, also for the
    !> memory a case is sized for before it is built (veslide_case).
    logical function auto_takes_device(method, memory, distributed) result(yes)
        integer, intent(in) :: method, memory
        logical, intent(in) :: distributed
        yes = gpu_visible() .and. .not. distributed .and. runs_on_device(method) .and. memory <= device_max_memory
    end function auto_takes_device

    !> `method` (SOLVER_*) refused, in the solver table's words, where it cannot take a case whose
    !> operator is `symmetric` or not, with the contact law `law` (LAW_* id): the one check of the
    !> input (veslide_config), of a case before it is built and of a solve
    subroutine method_check(method, symmetric, law, error)
        integer, intent(in) :: method, law
        logical, intent(in) :: symmetric
        type(error_t), allocatable, intent(out) :: error
        character(len=:), allocatable :: why
        why = method_refusal(method, symmetric, law)
        if (len(why) > 0) call fatal_error(error, "veslide:solver: "//why)
    end subroutine method_check

    !> The choice `choice` (DEVICE_*) refused where it cannot be had: 'gpu' in a build without GPU
    !> support, or where no GPU is visible (before anything is built for the case)
    subroutine check_device_choice(choice, error)
        integer, intent(in) :: choice
        type(error_t), allocatable, intent(out) :: error
        if (choice /= DEVICE_GPU) return
        if (.not. device_enabled) then
            call fatal_error(error, "veslide:solver: &solver device = 'gpu', but this build of veslide has no GPU"// &
                " support (build it with gpu/build.sh); allowed here: 'auto', 'cpu'")
        else if (device_count() == 0) then
            call fatal_error(error, "veslide:solver: &solver device = 'gpu', but no GPU is visible to this process"// &
                " (CUDA_VISIBLE_DEVICES, the driver); use 'auto' or 'cpu'")
        end if
    end subroutine check_device_choice

    !> Does 'auto' find a GPU: this build has one, and a device is visible (the emulated device
    !> is taken only when asked for by name)?
    logical function gpu_visible() result(yes)
        yes = .false.
        if (.not. device_enabled) return
        if (device_emulated()) return
        yes = device_count() > 0
    end function gpu_visible

    !> What the device does not run (the solver table): a method without device passes (pk), and
    !> Anderson mixing beyond the device passes' memory; the alternatives named for a case whose
    !> operator is `symmetric` or not, with the contact law `law`
    subroutine device_limits(method, o, symmetric, law, error)
        integer, intent(in) :: method, law
        type(solver_options_t), intent(in) :: o
        logical, intent(in) :: symmetric
        type(error_t), allocatable, intent(out) :: error
        character(len=:), allocatable :: why
        why = device_refusal(method, symmetric, law)
        if (len(why) == 0) why = memory_refusal(method, o%anderson_memory)
        if (len(why) > 0) call fatal_error(error, "veslide:solver: "//why)
    end subroutine device_limits

    !> The Anderson memory `method` (SOLVER_*) runs with when the options ask for `memory`
    !> (negative: the method's default, the solver table's: dr mixes 5 steps; pdr takes the
    !> over-relaxed plain step, which spends as many FFT pairs as mixing on the hard cases (within
    !> 1 %) and fewer on the paper scene, for 52 bytes per cell less, docs/solver-scaling.md)
    pure integer function default_anderson_memory(method, memory) result(m)
        integer, intent(in) :: method, memory
        type(solver_info_t) :: row
        m = memory
        if (m >= 0) return
        row = solver_info(method)
        m = row%anderson_default
    end function default_anderson_memory

    !> The method 'auto' takes for a problem (see the module's header)
    integer function auto_method(problem) result(method)
        type(contact_problem_t), intent(in) :: problem
        real(dp) :: spread
        spread = 1.0_dp        ! (the spread is measured only where the rule reads it)
        if (.not. problem%kernel%symmetric .and. problem%kernel%grid%cells() >= pdr_min_cells) &
            spread = problem%kernel%modulus_spread()
        method = auto_rule(problem%kernel%symmetric, problem%kernel%grid%cells(), spread, problem%law%kind)
    end function auto_method

    !> The rule of 'auto' for a kernel that is `symmetric` or not, on `cells` cells, whose modulus
    !> spread is `spread`, with the contact law `law` (LAW_* id; default the hard wall): bccg for a
    !> symmetric kernel, pdr on a large grid whose operator is not too anisotropic, dr otherwise, of
    !> these the first the solver table says takes the case (0 when none does)
    pure integer function auto_rule(symmetric, cells, spread, law) result(method)
        logical, intent(in) :: symmetric
        real(dp), intent(in) :: cells
        real(dp), intent(in) :: spread
        integer, intent(in), optional :: law
        integer :: law_, k
        integer :: order(4)
        law_ = LAW_HARD_WALL; if (present(law)) law_ = law
        if (symmetric) then
            order = [SOLVER_BCCG, SOLVER_PDR, SOLVER_DR, SOLVER_GCG]
        else if (cells >= pdr_min_cells .and. spread <= pdr_max_spread) then
            order = [SOLVER_PDR, SOLVER_DR, SOLVER_BCCG, SOLVER_GCG]
        else
            order = [SOLVER_DR, SOLVER_PDR, SOLVER_BCCG, SOLVER_GCG]
        end if
        method = 0
        do k = 1, size(order)
            if (method_takes(order(k), symmetric, law_)) then
                method = order(k); return
            end if
        end do
    end function auto_rule

    !> The methods a solve may run, known before its kernel is built (to size its memory): `method`
    !> itself, or for 'auto' what its rule takes for a kernel `symmetric` or not on `cells` cells
    !> whose spread is at most `spread_bound` (Einf/E0 for the spectral kernel of a viscoelastic
    !> solid; huge() when unknown), with the contact law `law` (default the hard wall): one method,
    !> or both pdr and dr when the bound does not decide
    pure function planned_methods(method, symmetric, cells, spread_bound, law) result(methods)
        integer, intent(in) :: method
        logical, intent(in) :: symmetric
        real(dp), intent(in) :: cells
        real(dp), intent(in) :: spread_bound
        integer, intent(in), optional :: law
        integer, allocatable :: methods(:)
        integer :: law_
        law_ = LAW_HARD_WALL; if (present(law)) law_ = law
        if (method /= SOLVER_AUTO) then
            methods = [method]
        else if (auto_rule(symmetric, cells, spread_bound, law_) /= auto_rule(symmetric, cells, 1.0_dp, law_)) then
            methods = [auto_rule(symmetric, cells, 1.0_dp, law_), auto_rule(symmetric, cells, spread_bound, law_)]
        else
            methods = [auto_rule(symmetric, cells, spread_bound, law_)]
        end if
    end function planned_methods

end module veslide_solver
