!> The solver table (veslide_solver_table): its rows as documented, the `auto` rule never
!> picking what the table refuses, and every refusal the same at the input, before a case is
!> built and at the solve (the one message naming &solver method, the reason and the methods that
!> take the case)
module test_veslide_solver_table
    use veslide_kinds, only: dp
    use veslide_error, only: fatal_error
    use veslide_contact_law, only: law_count, LAW_HARD_WALL, LAW_EXPONENTIAL, LAW_DUGDALE
    use veslide_solver_options, only: SOLVER_AUTO, SOLVER_PK, SOLVER_DR, SOLVER_BCCG, SOLVER_PDR, SOLVER_GCG
    use veslide_solver_table, only: solver_info_t, solver_info, solver_methods, method_takes, method_refusal, &
                                    device_refusal, memory_refusal, solver_bytes_per_cell, operator_symmetric, &
                                    runs_on_device
    use veslide_solver, only: auto_rule, planned_methods, pdr_min_cells, pdr_max_spread
    use veslide_config, only: config_t
    use veslide_case, only: case_t, run_case
    use veslide_study, only: run_study
    use testsuite, only: error_t, unittest_t, new_unittest, check
    use test_support, only: unique_name, remove
    use test_veslide_config, only: read_text
    implicit none
    private
    public :: collect_solver_table

    !> A small viscoelastic scene (16^2, the paper's solid) in namelist form; the method and the
    !> motion or sweep are appended
    character(len=*), parameter :: scene = "&grid nx = 16, ny = 16, lx_m = 0.01 / &surface k_cut = 4 /"// &
        " &material model = 'one_term', einf_pa = 1.0e8, ratio = 11.0, tau_s = 0.01, poisson = 0.5 /"// &
        " &load mean_pressure_pa = 3.0e4 /"

contains

    subroutine collect_solver_table(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("rows-as-documented", test_rows), &
            new_unittest("bytes-per-cell-as-the-memory-estimate-took-them", test_bytes), &
            new_unittest("auto-never-picks-a-refused-method", test_auto), &
            new_unittest("refusal-names-method-reason-and-alternatives", test_message), &
            new_unittest("input-and-solve-refuse-alike-in-motion", test_motion), &
            new_unittest("input-and-study-refuse-alike-for-sweep-speeds", test_sweep), &
            new_unittest("a-grid-the-motion-does-not-reach-is-symmetric", test_grid), &
            new_unittest("accepted-where-the-solve-takes-it", test_accepted), &
            new_unittest("device-refusals-from-the-table", test_device) &
            ]
    end subroutine collect_solver_table

    subroutine test_rows(error)
        type(error_t), allocatable, intent(out) :: error
        type(solver_info_t) :: r(4)
        integer :: k
        r = [(solver_info(solver_methods(k)), k=1, 4)]
        call check(error, all(r%method == [SOLVER_BCCG, SOLVER_PDR, SOLVER_DR, SOLVER_PK]), "rows' ids")
        if (allocated(error)) return
        call check(error, all(r%symmetric_only .eqv. [.true., .false., .false., .true.]), &
                   "bccg and pk need a symmetric operator, pdr and dr take any")
        if (allocated(error)) return
        call check(error, all(r%device .eqv. [.true., .true., .true., .false.]), "pk alone does not run on the device")
        if (allocated(error)) return
        do k = 1, 4
            call check(error, r(k)%laws(LAW_HARD_WALL), "every method takes the hard wall")
            if (allocated(error)) return
        end do
        call check(error, all(r%mixes .eqv. [.false., .true., .true., .false.]) .and. &
                   all(r%anderson_default == [0, 0, 5, 0]), "Anderson: dr mixes 5 by default, pdr 0")
        if (allocated(error)) return
        call check(error, .not. runs_on_device(SOLVER_PK) .and. runs_on_device(SOLVER_AUTO), "device column")
        if (allocated(error)) return
        ! gcg: the adhesive laws alone, on any operator (its splitting), on the host and the device
        r(1) = solver_info(SOLVER_GCG)
        call check(error, r(1)%method == SOLVER_GCG .and. .not. r(1)%symmetric_only .and. r(1)%device .and. &
                   r(1)%laws(LAW_EXPONENTIAL) .and. r(1)%laws(LAW_DUGDALE) .and. .not. r(1)%laws(LAW_HARD_WALL), &
                   "gcg: the adhesive laws, any operator, host and device")
    end subroutine test_rows

    !> The bytes the memory estimate took per solver before the table held them
    subroutine test_bytes(error)
        type(error_t), allocatable, intent(out) :: error
        call check(error, solver_bytes_per_cell(SOLVER_PK, -1, .false.), 16.0_dp, "pk"); if (allocated(error)) return
        call check(error, solver_bytes_per_cell(SOLVER_BCCG, -1, .false.), 36.0_dp, "bccg")
        if (allocated(error)) return
        call check(error, solver_bytes_per_cell(SOLVER_DR, -1, .false.), 40.0_dp + 8*5, "dr, its memory 5")
        if (allocated(error)) return
        call check(error, solver_bytes_per_cell(SOLVER_DR, 0, .false.), 40.0_dp, "dr, no mixing")
        if (allocated(error)) return
        call check(error, solver_bytes_per_cell(SOLVER_PDR, -1, .false.), 41.0_dp, "pdr, no mixing by default")
        if (allocated(error)) return
        call check(error, solver_bytes_per_cell(SOLVER_PDR, 3, .false.), 41.0_dp + 16 + 8*3, "pdr, memory 3")
        if (allocated(error)) return
        ! on the device (cuFFT's work area in u; M formed where read): pdr 8 more where the device
        ! has room (cuFFT's own work area), and with mixing always (Anderson's 16 and the area)
        call check(error, solver_bytes_per_cell(SOLVER_BCCG, -1, .true.), 25.0_dp, "bccg on the device")
        if (allocated(error)) return
        call check(error, solver_bytes_per_cell(SOLVER_BCCG, -1, .true., room=.true.), 25.0_dp, "bccg, room")
        if (allocated(error)) return
        call check(error, solver_bytes_per_cell(SOLVER_DR, 2, .true.), 40.0_dp + 8*2, "dr on the device")
        if (allocated(error)) return
        call check(error, solver_bytes_per_cell(SOLVER_DR, 2, .true., room=.true.), 40.0_dp + 8*2, "dr, room")
        if (allocated(error)) return
        call check(error, solver_bytes_per_cell(SOLVER_PDR, -1, .true.), 33.0_dp, "pdr on the device, lean")
        if (allocated(error)) return
        call check(error, solver_bytes_per_cell(SOLVER_PDR, -1, .true., room=.true.), 41.0_dp, "pdr, room")
        if (allocated(error)) return
        call check(error, solver_bytes_per_cell(SOLVER_PDR, 2, .true.), 33.0_dp + 24 + 8*2, "pdr on the device")
        if (allocated(error)) return
        call check(error, solver_bytes_per_cell(SOLVER_PDR, 2, .true., room=.true.), 33.0_dp + 24 + 8*2, "pdr, room")
    end subroutine test_bytes

    !> Whatever the operator, grid, anisotropy and law, 'auto' (and what the memory estimate plans
    !> for it) takes a method the table lets take the case
    subroutine test_auto(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp), parameter :: cells(4) = [2.0_dp, 64.0_dp**2, real(pdr_min_cells, dp), 2048.0_dp**2]
        real(dp), parameter :: spreads(4) = [1.0_dp, pdr_max_spread, pdr_max_spread*1.01_dp, 1.0e3_dp]
        integer, allocatable :: planned(:)
        integer :: i, j, law, m, k
        logical :: symmetric
        do law = 1, law_count
            do k = 0, 1
                symmetric = k == 1
                do i = 1, size(cells)
                    do j = 1, size(spreads)
                        m = auto_rule(symmetric, cells(i), spreads(j), law)
                        ! a method exactly where the table has one, and the refusal says so
                        call check(error, (m > 0) .eqv. method_takes(SOLVER_AUTO, symmetric, law), &
                                   "auto found no method where the table has one"); if (allocated(error)) return
                        if (m == 0) then
                            call check(error, len(method_refusal(SOLVER_AUTO, symmetric, law)) > 0, &
                                       "auto finds nothing, and the input check lets it through")
                            if (allocated(error)) return
                            cycle
                        end if
                        call check(error, method_takes(m, symmetric, law) .and. &
                                   len(method_refusal(m, symmetric, law)) == 0, "auto picked a method the table refuses")
                        if (allocated(error)) return
                        planned = planned_methods(SOLVER_AUTO, symmetric, cells(i), spreads(j), law)
                        call check(error, all([(method_takes(planned(m), symmetric, law), m=1, size(planned))]), &
                                   "the memory estimate plans for a method the table refuses")
                        if (allocated(error)) return
                    end do
                end do
            end do
        end do
        ! the rule itself, unchanged: bccg when symmetric, pdr on large moderately anisotropic
        ! operators, dr otherwise
        call check(error, auto_rule(.true., 4.0_dp, 1.0_dp, LAW_EXPONENTIAL) == SOLVER_GCG .and. &
                   auto_rule(.true., 4.0_dp, 1.0_dp, LAW_DUGDALE) == SOLVER_GCG .and. &
                   auto_rule(.false., 4.0_dp, 1.0_dp, LAW_DUGDALE) == SOLVER_GCG, "auto and the adhesive laws")
        if (allocated(error)) return
        call check(error, auto_rule(.true., 4.0_dp, 1.0_dp) == SOLVER_BCCG .and. &
                   auto_rule(.false., real(pdr_min_cells, dp), 2.0_dp) == SOLVER_PDR .and. &
                   auto_rule(.false., real(pdr_min_cells, dp), 1.0e3_dp) == SOLVER_DR .and. &
                   auto_rule(.false., 64.0_dp, 2.0_dp) == SOLVER_DR, "the auto rule changed")
    end subroutine test_auto

    subroutine test_message(error)
        type(error_t), allocatable, intent(out) :: error
        character(len=:), allocatable :: m
        m = method_refusal(SOLVER_BCCG, .false., LAW_HARD_WALL)
        call check(error, index(m, "&solver method = 'bccg'") == 1 .and. index(m, "not symmetric") > 0 .and. &
                   index(m, "'auto', 'pdr' and 'dr'") > 0, "bccg in motion: "//m)
        if (allocated(error)) return
        m = method_refusal(SOLVER_PK, .false., LAW_HARD_WALL)
        call check(error, index(m, "&solver method = 'pk'") == 1 .and. index(m, "'auto', 'pdr' and 'dr'") > 0, &
                   "pk in motion: "//m)
        if (allocated(error)) return
        call check(error, len(method_refusal(SOLVER_PK, .true., LAW_HARD_WALL)) == 0 .and. &
                   len(method_refusal(SOLVER_DR, .false., LAW_HARD_WALL)) == 0 .and. &
                   len(method_refusal(SOLVER_AUTO, .false., LAW_HARD_WALL)) == 0, "a refusal where none is due")
        if (allocated(error)) return
        ! a law no method takes: every method refused by the law's name, 'auto' too
        m = method_refusal(SOLVER_DR, .false., law_count + 1)
        call check(error, index(m, "does not take the contact law of id") > 0 .and. index(m, ": none") > 0, &
                   "a law no method takes: "//m)
        if (allocated(error)) return
        m = method_refusal(SOLVER_AUTO, .true., law_count + 1)
        call check(error, index(m, "&solver method = 'auto' finds no method that takes the contact law") == 1, &
                   "'auto' for a law no method takes: "//m)
        if (allocated(error)) return
        call check(error, operator_symmetric(.true., [0.1_dp]) .and. operator_symmetric(.false., [0.0_dp, 0.0_dp]) &
                   .and. .not. operator_symmetric(.false., [0.0_dp, 0.1_dp]), "the symmetric operator")
    end subroutine test_message

    !> pk and bccg for a viscoelastic solid in motion: the input refuses it, and a case that
    !> skipped the input's check is refused at the solve, in the same words
    subroutine test_motion(error)
        type(error_t), allocatable, intent(out) :: error
        character(len=4), parameter :: methods(2) = ['pk  ', 'bccg']
        integer :: k
        do k = 1, size(methods)
            call same_refusal(trim(methods(k)), scene//" &motion speed_m_s = 0.1 / &solver method = '"// &
                              trim(methods(k))//"' /", .false., error)
            if (allocated(error)) return
        end do
    end subroutine test_motion

    !> The same when only &sweep speeds move the solid: the input refuses it, and the study that
    !> skipped the check fails at its first case in motion, in the same words
    subroutine test_sweep(error)
        type(error_t), allocatable, intent(out) :: error
        call same_refusal('sweep', scene//" &sweep speeds_m_s = 0.0, 0.1 / &solver method = 'bccg' /", .true., error)
    end subroutine test_sweep

    !> On a grid of 2 cells along x sliding along x every mode is the mean or a Nyquist line along
    !> the motion, which the kernel keeps real: the input takes bccg there, and so does the solve;
    !> at an angle the motion reaches the rows' modes, and both refuse it alike
    subroutine test_grid(error)
        type(error_t), allocatable, intent(out) :: error
        character(len=*), parameter :: two = "&grid nx = 2, ny = 16, lx_m = 0.01, ly_m = 0.01 / &surface kind = 'flat' /"// &
            " &material model = 'one_term', einf_pa = 1.0e8, ratio = 11.0, tau_s = 0.01, poisson = 0.5 /"
        type(config_t) :: cfg
        type(case_t) :: c
        call read_text('grid', two//" &motion speed_m_s = 0.1 / &solver method = 'bccg' /", cfg, error)
        if (allocated(error)) return
        call run_case(cfg, c, error); if (allocated(error)) return
        call check(error, c%kernel%symmetric .and. c%state%method == 'bccg' .and. c%state%converged, &
                   "a moving viscoelastic solid on 2 x 16 cells sliding along x: not solved by bccg")
        if (allocated(error)) return
        call same_refusal('grid-angle', two//" &motion speed_m_s = 0.1, direction_deg = 30.0 / &solver method = 'bccg' /", &
                          .false., error)
    end subroutine test_grid

    !> What the solve takes, the input takes: a solid at rest (also swept at speed 0 only) for
    !> bccg and pk, an elastic one in motion, the splittings and 'auto' in motion
    subroutine test_accepted(error)
        type(error_t), allocatable, intent(out) :: error
        character(len=*), parameter :: elastic = "&grid nx = 16, ny = 16, lx_m = 0.01 / &surface k_cut = 4 /"// &
            " &material model = 'elastic', young_pa = 3.0e6 / &load mean_pressure_pa = 3.0e4 /"
        character(len=100), parameter :: tails(7) = [character(len=100) :: &
            "&motion speed_m_s = 0.0 / &solver method = 'bccg' /", &
            "&motion speed_m_s = 0.0 / &solver method = 'pk' /", &
            "&sweep speeds_m_s = 0.0 / &solver method = 'bccg' /", &
            "&motion speed_m_s = 0.1 / &solver method = 'dr' /", &
            "&motion speed_m_s = 0.1 / &solver method = 'pdr' /", &
            "&motion speed_m_s = 0.1 / &solver method = 'auto' /", &
            "&sweep speeds_m_s = 0.0, 0.1 / &solver method = 'auto' /"]
        type(config_t) :: cfg
        type(case_t) :: c
        integer :: k
        do k = 1, size(tails)
            call read_text('accepted', scene//" "//trim(tails(k)), cfg, error)
            if (allocated(error)) then
                error%message = trim(tails(k))//": "//error%message; return
            end if
            if (index(tails(k), '&sweep') > 0) cycle
            call run_case(cfg, c, error)
            if (allocated(error)) then
                error%message = trim(tails(k))//" solved: "//error%message; return
            end if
        end do
        call read_text('accepted', elastic//" &motion speed_m_s = 0.1 / &solver method = 'pk' /", cfg, error)
        if (allocated(error)) return
        call run_case(cfg, c, error)
    end subroutine test_accepted

    !> What the device does not run, in the table's words (the refusals themselves, before a
    !> case is built and at the solve: the suite `device`)
    subroutine test_device(error)
        type(error_t), allocatable, intent(out) :: error
        character(len=:), allocatable :: m
        m = device_refusal(SOLVER_PK, .true., LAW_HARD_WALL)
        call check(error, index(m, "&solver method = 'pk' does not run on the device") == 1 .and. &
                   index(m, "'auto', 'bccg', 'pdr' and 'dr'") > 0 .and. index(m, "&solver device = 'cpu'") > 0, &
                   "pk on the device: "//m)
        if (allocated(error)) return
        m = device_refusal(SOLVER_PK, .false., LAW_HARD_WALL)
        call check(error, index(m, "'auto', 'pdr' and 'dr'") > 0, "pk on the device, in motion: "//m)
        if (allocated(error)) return
        call check(error, len(device_refusal(SOLVER_BCCG, .true., LAW_HARD_WALL)) == 0 .and. &
                   len(device_refusal(SOLVER_AUTO, .false., LAW_HARD_WALL)) == 0, "a device refusal where none is due")
        if (allocated(error)) return
        call check(error, index(memory_refusal(SOLVER_DR, 9), "&solver anderson_memory = 9") == 1 .and. &
                   len(memory_refusal(SOLVER_PDR, 8)) == 0 .and. len(memory_refusal(SOLVER_BCCG, 9)) == 0, &
                   "Anderson memory on the device")
    end subroutine test_device

    ! ---- helpers -------------------------------------------------------------------------

    !> `text` refused at the input, and the same case (a study when `study`) with the input's
    !> check skipped refused when solved: the two messages the same from "&solver method" on
    subroutine same_refusal(tag, text, study, error)
        character(len=*), intent(in) :: tag, text
        logical, intent(in) :: study
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg, skipped
        type(error_t), allocatable :: at_input, at_solve
        type(case_t) :: c
        character(len=:), allocatable :: a, b, path
        integer :: nfail
        call read_text(tag, text, cfg, at_input)
        if (.not. allocated(at_input)) then
            call fatal_error(error, tag//": not refused at the input"); return
        end if
        ! the same input with 'auto' passes the check; its method is set afterwards
        call read_text(tag, text(1:index(text, "&solver") - 1)//"&solver method = 'auto' /", skipped, error)
        if (allocated(error)) return
        skipped%solver%method = text(index(text, "method = '") + 10:index(text, "' /", back=.true.) - 1)
        if (study) then
            path = unique_name(tag//'.h5')
            call run_study(skipped, path, nfail, at_solve)
            call remove(path); call remove(path//'.resume')      ! (a failed study keeps its part file)
        else
            call run_case(skipped, c, at_solve)
        end if
        if (.not. allocated(at_solve)) then
            call fatal_error(error, tag//": the solve took what the input refused: "//at_input%message); return
        end if
        a = at_input%message(index(at_input%message, "&solver method"):)
        b = at_solve%message(max(1, index(at_solve%message, "&solver method")):)
        call check(error, a == b .and. index(at_input%message, "&solver method") > 0, &
                   tag//": the input and the solve refuse differently: '"//at_input%message//"' and '"// &
                   at_solve%message//"'")
    end subroutine same_refusal

end module test_veslide_solver_table
