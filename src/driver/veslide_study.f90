!> Parameter studies: every combination of the &sweep lists in one run.
!>
!> The study is enumerated up front as a list of speed chains (seed x temperature x eccentricity
!> x angle x pressure, seed-major), each run through its speeds in the order given, warm-started
!> along speed; then one loop over the chains (all of them, or one rank's share) and one row
!> writer. Each case is a specification of its own (`chain_spec`: the input's, with the chain's
!> values and the speed set on a copy); the configuration is only read.
!> With an adhesive law, a list of loads (&sweep pressures_pa, or approaches_m under approach
!> control) is a load path instead: one chain per (seed, temperature, eccentricity, angle, speed)
!> runs through the loads in the order given, each case warm-started from the previous one in
!> either direction, so that it follows the branch it is on (hysteresis); jump-in and jump-out
!> between consecutive cases are flagged in /summary (path_step, path_jump), with the contact
!> patches made, lost and bistable (held the other way at the same load earlier on the path), and
!> each path's pull-off and first jump-in tabulated in /paths. A path is one chain: it stays on one rank.
!> Each surface is generated once per (seed, eccentricity, angle), each speed's kernel built once.
!> On the device a chain's fields stay there from speed to speed (solve_contact's `keep`): the next
!> speed's warm start is formed from the last case's p and g where they are, and the heights
!> stay; only the next kernel's multiplier goes up (24 bytes per cell of uploads saved per case
!> after a chain's first; p, u, g still come down for the case's results).
!> Every finished case is written at once under /cases/NNNNNN with its parameters and appended as
!> a row of /summary (case, seed, parameters, every scalar of the case; int64 where integer), then
!> flushed; with several seeds, /ensemble holds n_seeds and the mean and standard error over seeds
!> of every scalar (axes averaged as axial data). Progress goes to a callback the application
!> supplies: the library never prints. Rank files of a distributed study are joined by
!> `merge_study_parts`, with the same row and ensemble code.
module veslide_study
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use veslide_kinds, only: dp, i8, pi, radians
    use veslide_error, only: error_t, fatal_error, add_context
    use veslide_clock, only: wall_seconds
    use veslide_config, only: config_t, case_speeds
    use veslide_grid, only: grid_t
    use veslide_fftw, only: fft2d_t
    use veslide_kernel, only: kernel_t
    use veslide_case_data, only: case_spec_t, material_spec_t
    use veslide_case_spec, only: case_spec_of, resolve_material
    use veslide_memory, only: size_and_check_memory
    use veslide_hdf5, only: h5file_t
    use veslide_output, only: write_provenance, discard_output
    use veslide_system, only: path_kind, PATH_REGULAR, use_threads, defer_termination, allow_termination
    use veslide_version, only: version_string
    use veslide_quantities, only: results_t, axial_of, AXIAL_NONE, AXIAL_HALF_TURN
    use veslide_quantities, only: case_results
    use veslide_case_file, only: write_case_group
    use veslide_case, only: case_t, build_surface, build_kernel, case_grid, solve_prepared
    use veslide_contact, only: contact_fields_t
    use veslide_case_file, only: write_warnings
    use veslide_validity, only: check_surface_scale
    use veslide_warning, only: warning_t
    use veslide_patches, only: patch_changes, cell_set_t, cell_set
    use veslide_strings, only: str
    implicit none
    private
    public :: study_plan_t, study_progress_t, progress_callback, plan_study, run_study, merge_study_parts, &
              seed_statistics, write_ensemble, chain_spec, param_names, param_units, plan_study_transforms, &
              path_jump, write_paths, JUMP_IN, JUMP_OUT

    !> The parameter columns that lead every /summary row; temperature_c (the 7th) in the studies
    !> of a material with a temperature shift (whose temperature may be swept). The attribute
    !> `parameters` of /summary (and of /ensemble, without case and seed) names them for readers.
    character(len=*), parameter :: param_names(7) = [character(len=13) :: 'case', 'seed', 'eccentricity', &
                                                     'alpha_deg', 'pressure_pa', 'speed_m_s', 'temperature_c']
    character(len=*), parameter :: param_units(7) = [character(len=6) :: '-', '-', '-', 'degree', 'Pa', 'm/s', 'degC']

    !> The events path_jump flags between consecutive cases of a load path: the contact made (from
    !> none, or to full contact) or lost (to none, to a case that did not converge, or from full
    !> contact)
    integer, parameter :: JUMP_IN = 1, JUMP_OUT = -1
    !> The columns a load path adds at the end of /summary (docs/output.md)
    character(len=64), parameter :: path_columns(7) = [character(len=64) :: 'path_step', 'path_jump', &
        'path_patches_made', 'path_patches_lost', 'path_patch_cells_made', 'path_patch_cells_lost', 'path_patches_bistable']

    !> One chain: a surface and a load run through every speed, or (a load path) a surface and a
    !> speed run through every load
    type :: study_chain_t
        integer(i8) :: seed = 0_i8
        real(dp) :: eccentricity = 0.0_dp, alpha_deg = 0.0_dp, pressure_pa = 0.0_dp
        real(dp) :: temperature_c = 0.0_dp
        integer :: first_case = 0          !! global number of its first case; speeds (or loads) follow
        integer :: speed_index = 0         !! a load path's speed (index into the plan's speeds); 0 otherwise
    end type study_chain_t

    type :: study_plan_t
        type(study_chain_t), allocatable :: chains(:)
        real(dp), allocatable :: speeds(:)
        integer(i8), allocatable :: seeds(:)
        integer :: ncase = 0
        integer :: nparam = 6                  !! parameter columns (7 with temperature_c)
        !> a load path (an adhesive law with &sweep pressures_pa or approaches_m): each chain runs
        !> through `loads` in the order given, at one speed
        logical :: path = .false.
        logical :: approach = .false.          !! the path's loads are approaches [m] (approach control)
        real(dp), allocatable :: loads(:)      !! the path: pressures [Pa] or approaches [m]
        integer :: nstep = 0                   !! cases per chain: the speeds, or the path's loads
    end type study_plan_t

    !> What a progress callback is told after each case
    type :: study_progress_t
        !> cases of this process's share finished (those kept from the part file of a resumed
        !> study included), and its share
        integer :: done = 0, total = 0
        integer :: resumed = 0                      !! of them, kept from the part file
        !> the case reported; 0 for the one call before any case, made when a study resumes
        real(dp) :: elapsed_s = 0.0_dp, case_s = 0.0_dp
        integer :: case_number = 0
        integer(i8) :: seed = 0_i8
        real(dp) :: eccentricity = 0.0_dp, alpha_deg = 0.0_dp, pressure_pa = 0.0_dp, speed_m_s = 0.0_dp
        real(dp) :: contact_area_fraction = 0.0_dp, friction_coefficient = 0.0_dp
        integer :: operator_applications = 0
        logical :: converged = .false.
        !> a load path's: the case's place on it (0 outside a path), its event (JUMP_IN, JUMP_OUT
        !> or 0), its bistable patches (path_patches_bistable), and under approach control the
        !> approach given [m] (pressure_pa is then the load the case carried)
        integer :: path_step = 0, path_jump = 0, path_bistable = 0
        real(dp) :: approach_m = huge(1.0_dp)
        !> what the case's validity measures warn of (its input's warnings are the study's, said once)
        type(warning_t), allocatable :: warnings(:)
    end type study_progress_t

    abstract interface
        subroutine progress_callback(info)
            import :: study_progress_t
            type(study_progress_t), intent(in) :: info
        end subroutine progress_callback
    end interface

contains

    !> The chains of the study of `cfg` (lists of &sweep, or the single values of their groups)
    subroutine plan_study(cfg, plan)
        type(config_t), intent(in) :: cfg
        type(study_plan_t), intent(out) :: plan
        real(dp), allocatable :: alphas(:), eccs(:), pressures(:), temps(:)
        integer :: is, ie, ia, ip, it, iv, k, nv
        plan%speeds = case_speeds(cfg)
        alphas = list_or(cfg%sweep%alphas, cfg%surface%alpha_deg)
        eccs = list_or(cfg%sweep%eccentricities, cfg%surface%eccentricity)
        plan%path = cfg%adhesion%law /= 'none' .and. size(cfg%sweep%pressures) + size(cfg%sweep%approaches) > 0
        if (plan%path) then
            ! the loads are the path within a chain; a chain per speed
            plan%approach = size(cfg%sweep%approaches) > 0
            if (plan%approach) then
                plan%loads = cfg%sweep%approaches
            else
                plan%loads = cfg%sweep%pressures
            end if
            pressures = [cfg%load%mean_pressure_pa]
            nv = size(plan%speeds); plan%nstep = size(plan%loads)
        else
            pressures = list_or(cfg%sweep%pressures, cfg%load%mean_pressure_pa)
            nv = 1; plan%nstep = size(plan%speeds)
        end if
        temps = list_or(cfg%sweep%temperatures, cfg%material%temperature_c)
        if (size(cfg%sweep%seeds) > 0) then
            plan%seeds = cfg%sweep%seeds
        else
            plan%seeds = [cfg%surface%seed]
        end if
        allocate (plan%chains(size(plan%seeds)*size(eccs)*size(alphas)*size(pressures)*size(temps)*nv))
        plan%nparam = merge(7, 6, cfg%material%shift /= 'none')
        k = 0
        ! seeds outermost (the ensemble's rows), then temperatures (each temperature's kernels built
        ! once per seed), then the surface's spectrum and the load
        do is = 1, size(plan%seeds)
            do it = 1, size(temps)
                do ie = 1, size(eccs)
                    do ia = 1, size(alphas)
                        do ip = 1, size(pressures)
                            do iv = 1, nv
                                k = k + 1
                                plan%chains(k) = study_chain_t(plan%seeds(is), eccs(ie), alphas(ia), pressures(ip), &
                                                               temps(it), (k - 1)*plan%nstep + 1, &
                                                               merge(iv, 0, plan%path))
                            end do
                        end do
                    end do
                end do
            end do
        end do
        plan%ncase = size(plan%chains)*plan%nstep
    contains
        pure function list_or(list, single) result(v)
            real(dp), intent(in) :: list(:), single
            real(dp), allocatable :: v(:)
            if (size(list) > 0) then
                v = list
            else
                v = [single]
            end if
        end function list_or
    end subroutine plan_study

    !> The specification of the case of `chain` at `speed`: the study's input `base` with the
    !> chain's seed, spectrum, load and solid (`mat`, resolved at its temperature)
    pure function chain_spec(base, chain, mat, speed) result(spec)
        type(case_spec_t), intent(in) :: base
        type(study_chain_t), intent(in) :: chain
        type(material_spec_t), intent(in) :: mat
        real(dp), intent(in) :: speed
        type(case_spec_t) :: spec
        spec = base
        spec%surface%seed = chain%seed
        spec%surface%eccentricity = chain%eccentricity
        spec%surface%alpha_rad = radians(chain%alpha_deg)
        spec%mean_pressure_pa = chain%pressure_pa
        spec%material = mat
        spec%speed_m_s = speed
    end function chain_spec

    !> The FFT plans of the study's grid, made (measured, unless &solver fft_planner = 'estimate')
    !> and kept in the machine's wisdom file before any case runs. The first process of an MPI
    !> study calls it before the others start: every rank then plans from the same wisdom, as every
    !> later run does (each rank measuring its own could choose plans of other rounding)
    subroutine plan_study_transforms(cfg, error)
        type(config_t), intent(in) :: cfg
        type(error_t), allocatable, intent(out) :: error
        type(case_spec_t) :: base
        type(fft2d_t) :: fft
        call case_spec_of(cfg, base, error); if (allocated(error)) return
        call use_threads(base%threads)
        call fft%init(base%nx, base%ny, error, planner=base%fft_planner); if (allocated(error)) return
        call fft%destroy()
    end subroutine plan_study_transforms

    !> Run the study of `cfg` into the (temporary) HDF5 file `path`; `nfail` counts cases that
    !> did not converge. `part` = [rank, nranks] runs only the chains whose index is rank modulo
    !> nranks, with global case numbers (a rank file of a distributed study: no /ensemble).
    subroutine run_study(cfg, path, nfail, error, progress, part, stop_after, node_ranks)
        type(config_t), intent(in) :: cfg
        character(len=*), intent(in) :: path
        integer, intent(out) :: nfail
        type(error_t), allocatable, intent(out) :: error
        procedure(progress_callback), optional :: progress
        integer, intent(in), optional :: part(2)
        !> stop after this many new cases, leaving the part file as a killed run would (the next
        !> run resumes from it); a study that stops early writes no /ensemble
        integer, intent(in), optional :: stop_after
        !> the processes of an MPI study on this machine, which share its free memory (default 1)
        integer, intent(in), optional :: node_ranks
        type(study_plan_t) :: plan
        type(grid_t) :: grid
        type(kernel_t), allocatable :: kernels(:)
        real(dp), allocatable :: kernel_seconds(:), h(:, :), p_prev(:, :), g_prev(:, :)
        integer(i8), allocatable :: table(:, :)
        character(len=64), allocatable :: columns(:), units(:)
        logical, allocatable :: is_int(:)
        type(case_spec_t) :: base, spec
        type(material_spec_t) :: mat
        type(fft2d_t) :: fft
        type(h5file_t) :: f
        type(case_t) :: c
        !> the device's fields of a chain's last case: the next speed starts from its p and g there
        type(contact_fields_t) :: kept
        type(results_t) :: r
        type(study_progress_t) :: info
        type(study_chain_t) :: ch
        integer :: ic, iv, is, k, j, rank, nranks, nmine, nrow, jump_now
        !> a load path's patches made and lost since its previous case, their cells, and how many
        !> of them are bistable (the path held them the other way at the same control before)
        integer :: patches(2), bistable
        integer(i8) :: patch_cells(2)
        !> the closed cells of the path's converged cases whose control recurs later on the path,
        !> and their places on it: the states a later case at the same control is compared with
        type(cell_set_t), allocatable :: seen(:)
        integer, allocatable :: seen_step(:)
        integer, allocatable :: keep(:)
        logical, allocatable :: done(:)
        integer(i8) :: surface_seed, estimate
        real(dp) :: surface_ecc, surface_alpha, t_start, t_case, kernels_temperature, surface_slope
        logical :: have_surface, warm

        nfail = 0
        rank = 0; nranks = 1
        if (present(part)) then
            rank = part(1); nranks = max(1, part(2))
        end if
        call plan_study(cfg, plan)
        nmine = count([(modulo(ic - 1, nranks) == rank, ic = 1, size(plan%chains))])*plan%nstep

        call case_spec_of(cfg, base, error); if (allocated(error)) return
        call size_and_check_memory(base, estimate, error, node_ranks=node_ranks, speeds=plan%speeds)
        if (allocated(error)) return
        have_surface = .false.; surface_slope = -1.0_dp
        if (base%surface%kind == 'file') then         ! read once: every case has the same heights
            call build_surface(base, h, error); if (allocated(error)) return
            have_surface = .true.
        end if
        call case_grid(base, grid, error); if (allocated(error)) return
        allocate (kernels(size(plan%speeds)), kernel_seconds(size(plan%speeds)))
        kernels_temperature = huge(1.0_dp)
        allocate (done(plan%ncase)); done = .false.
        nrow = 0
        if (path_kind(path) == PATH_REGULAR) then
            call resume_part(error); if (allocated(error)) return
        else
            call f%open(path, 'w', error); if (allocated(error)) return
            call write_provenance(f, cfg%path, cfg%text, plan%seeds, error, study=.true., &
                                  preparation=cfg%surface%preparation); if (allocated(error)) return
            call write_warnings(f, '', base%warnings, error); if (allocated(error)) return
        end if
        call use_threads(base%threads)
        call fft%init(grid%nx, grid%ny, error, planner=base%fft_planner)
        if (allocated(error)) return
        if (have_surface) then
            call check_surface_scale(base, grid, fft, h, error, surface_slope); if (allocated(error)) return
        end if

        ! (the file as it stands is complete: a stop during a solve, where termination is let
        ! through, leaves it readable and resumable; a program that defers termination around the
        ! study, as veslide does, lets it through only there)
        call f%flush(error); if (allocated(error)) return
        t_start = wall_seconds()
        info%total = nmine; info%resumed = count(done); info%done = info%resumed
        if (info%resumed > 0 .and. present(progress)) call progress(info)
        surface_seed = -huge(1_i8); surface_ecc = -1.0_dp; surface_alpha = -huge(1.0_dp)
        do ic = 1, size(plan%chains)
            if (modulo(ic - 1, nranks) /= rank) cycle
            associate (chain => plan%chains(ic))
                ! the material, and each speed's kernel, at the chain's temperature (built once
                ! for a study without a temperature sweep)
                if (chain%temperature_c /= kernels_temperature) then
                    call resolve_material(cfg%material, chain%temperature_c, mat, error)
                    call add_context(error, "veslide: "//cfg%path//": &material: ")
                    if (allocated(error)) return
                    do iv = 1, size(plan%speeds)
                        call build_kernel(chain_spec(base, chain, mat, plan%speeds(iv)), grid, kernels(iv), &
                                          kernel_seconds(iv), error)
                        if (allocated(error)) return
                    end do
                    kernels_temperature = chain%temperature_c
                end if
                spec = chain_spec(base, chain, mat, plan%speeds(1))
                if (spec%surface%kind /= 'file' .and. .not. (have_surface .and. chain%seed == surface_seed .and. &
                    chain%eccentricity == surface_ecc .and. chain%alpha_deg == surface_alpha)) then
                    call build_surface(spec, h, error); if (allocated(error)) return
                    call check_surface_scale(spec, grid, fft, h, error, surface_slope)
                    if (allocated(error)) return
                    have_surface = .true.
                    surface_seed = chain%seed; surface_ecc = chain%eccentricity; surface_alpha = chain%alpha_deg
                end if
                seen = [cell_set_t ::]; seen_step = [integer ::]
                do is = 1, plan%nstep
                    k = chain%first_case + is - 1
                    if (done(k)) cycle
                    if (present(stop_after)) then
                        if (info%done - info%resumed >= stop_after) then
                            call kept%finish(); call f%close(error); return
                        end if
                    end if
                    ! the case's speed and load: a speed chain's speed, or a load path's load
                    iv = is
                    ch = chain
                    if (plan%path) then
                        iv = chain%speed_index
                        if (plan%approach) then    ! (the load is the result: no parameter)
                            ch%pressure_pa = ieee_value(0.0_dp, ieee_quiet_nan)
                        else
                            ch%pressure_pa = plan%loads(is)
                        end if
                    end if
                    if (is > 1 .and. .not. allocated(p_prev)) call restore_warm_start(k - 1, is)
                    c%spec = chain_spec(base, ch, mat, plan%speeds(iv))
                    if (plan%approach) then
                        c%spec%approach_m = plan%loads(is); c%spec%mean_pressure_pa = 0.0_dp
                    end if
                    c%h = h; c%surface_rms_slope = surface_slope
                    c%kernel = kernels(iv); c%kernel_seconds = kernel_seconds(iv)
                    c%memory_estimate_bytes = estimate
                    t_case = wall_seconds()
                    warm = is > 1 .and. cfg%sweep%warm_start .and. allocated(p_prev)
                    ! under load control, a path whose last case lost the contact (the gap opened
                    ! without bound, or no cell closed) stays apart under tension (warm-started from
                    ! the separation) and comes back from first contact under a compressive or zero
                    ! load (a cold start)
                    if (warm .and. plan%path .and. .not. plan%approach) then
                        if (separated(k - 1)) warm = c%spec%mean_pressure_pa < 0.0_dp
                    end if
                    ! (on the device the fields stay from case to case of the chain: the warm
                    ! start is formed there from the last case's p and g, the heights stay)
                    call allow_termination()
                    if (warm) then
                        call solve_prepared(fft, c, error, p_init=p_prev, g_init=g_prev, keep=kept, same_heights=.true.)
                    else
                        call solve_prepared(fft, c, error, keep=kept)
                    end if
                    call defer_termination()
                    if (allocated(error)) then
                        call kept%finish(); return
                    end if
                    ! (a load path: the contact patches made and lost since its previous case,
                    ! from the two cases' closed cells; between two converged cases, those the
                    ! path held the other way at the same control before)
                    patches = 0; patch_cells = 0_i8; bistable = 0
                    if (plan%path .and. is > 1 .and. allocated(g_prev)) then
                        call patch_changes(g_prev <= 0.0_dp, c%state%g <= 0.0_dp, patches(1), patches(2), &
                                           patch_cells(1), patch_cells(2), &
                                           at_before=pack(seen, seen_step < is - 1 .and. &
                                                          plan%loads(seen_step) == plan%loads(is - 1)), &
                                           at_after=pack(seen, plan%loads(seen_step) == plan%loads(is)), &
                                           bistable=bistable)
                        if (.not. (c%state%converged .and. converged_case(k - 1))) bistable = 0
                    end if
                    if (plan%path .and. c%state%converged) then
                        if (any(plan%loads(is + 1:) == plan%loads(is))) then
                            seen = [seen, cell_set(c%state%g <= 0.0_dp)]; seen_step = [seen_step, is]
                        end if
                    end if
                    p_prev = c%state%p; g_prev = c%state%g
                    if (.not. c%state%converged) nfail = nfail + 1
                    call case_results(c, r)
                    call write_row(k, ch, plan%speeds(iv), is, error); if (allocated(error)) return
                    ! (a load path keeps it without warm starts too: the next case's patch counts)
                    if (is < plan%nstep .and. (cfg%sweep%warm_start .or. plan%path)) then
                        call save_warm_start(k, error); if (allocated(error)) return
                    end if
                    info%done = info%done + 1
                    if (present(progress)) then
                        info%elapsed_s = wall_seconds() - t_start
                        info%case_s = wall_seconds() - t_case; info%case_number = k
                        info%seed = chain%seed; info%eccentricity = chain%eccentricity
                        info%alpha_deg = chain%alpha_deg; info%pressure_pa = ch%pressure_pa
                        info%speed_m_s = plan%speeds(iv)
                        if (plan%path) then
                            info%path_step = is; info%path_jump = jump_now; info%path_bistable = bistable
                            if (plan%approach) then
                                info%approach_m = plan%loads(is); info%pressure_pa = r%get('mean_pressure_pa')
                            end if
                        end if
                        info%contact_area_fraction = r%get('contact_area_fraction')
                        info%friction_coefficient = r%get('friction_coefficient')
                        info%operator_applications = c%state%operator_applications
                        info%converged = c%state%converged
                        info%warnings = pack(c%warnings, [(c%warnings(j)%source == 'validity', j = 1, &
                                                           size(c%warnings))])
                        call progress(info)
                    end if
                end do
                if (allocated(p_prev)) deallocate (p_prev, g_prev)
                call kept%finish()
            end associate
        end do
        call discard_output(path//'.resume')
        if (size(plan%seeds) > 1 .and. nranks == 1) then
            call write_ensemble(f, columns, units, is_int, table(:, 1:nrow), size(plan%seeds), error)
            if (allocated(error)) return
        end if
        if (plan%path .and. nranks == 1 .and. nrow == plan%ncase) then
            call write_paths(f, columns, units, is_int, table(:, 1:nrow), plan, error); if (allocated(error)) return
        end if
        call f%close(error)
        call fft%destroy()

    contains

        !> Continue the part file of a killed run of the same study: it must hold the same input
        !> text and come from the same veslide version; its finished cases (the rows of /summary)
        !> are kept, a case group left half-written is removed
        subroutine resume_part(error)
            type(error_t), allocatable, intent(out) :: error
            character(len=:), allocatable :: text, version
            integer(i8), allocatable :: rows(:, :)
            integer :: kk
            character(len=16) :: tag
            call f%open(path, 'rw', error)
            if (allocated(error)) then
                call fatal_error(error, "veslide: '"//path//"' is left by an earlier run but is not a readable"// &
                                " HDF5 file: remove it to start afresh"); return
            end if
            call f%read_text('/input/namelist', text, error)
            if (.not. allocated(error)) call f%read_attr_text('/', 'veslide_version', version, error)
            if (allocated(error)) then
                call fatal_error(error, "veslide: '"//path//"' is left by an earlier run but holds no study input:"// &
                                " remove it to start afresh"); return
            end if
            if (text /= cfg%text .or. version /= version_string()) then
                call fatal_error(error, "veslide: '"//path//"' is the part file of another input or veslide version"// &
                    " (it cannot be resumed by this run): rerun its own input, or remove it to start afresh"); return
            end if
            if (f%exists('/summary')) then
                call f%read_table('/summary', columns, is_int, rows, error); if (allocated(error)) return
                ! (a part file of an earlier build of the same version whose load path had fewer
                ! columns: the rows of this run would not fit its table)
                if (plan%path) then
                    if (size(columns) < size(path_columns)) then
                        kk = 0
                    else
                        kk = count(columns(size(columns) - size(path_columns) + 1:) == path_columns)
                    end if
                    if (kk /= size(path_columns)) then
                        call fatal_error(error, "veslide: '"//path//"' is the part file of another build of veslide"// &
                            " (its /summary lacks the load path's columns of this one): remove it to start afresh")
                        return
                    end if
                end if
                allocate (units(size(columns)))
                call f%read_attr_text_list('/summary', 'units', units, error); if (allocated(error)) return
                allocate (table(size(columns), nmine))
                do kk = 1, size(rows, 2)
                    done(int(rows(1, kk))) = .true.
                    nrow = nrow + 1
                    table(:, nrow) = rows(:, kk)
                end do
            end if
            do kk = 1, plan%ncase
                write (tag, '("/cases/",i6.6)') kk
                if (.not. done(kk)) call f%delete(trim(tag))
            end do
        end subroutine resume_part

        !> The pressure and gap of case k, from which the chain's next speed starts if the run is
        !> killed now (a small file beside the part file, removed when the study completes)
        subroutine save_warm_start(k, error)
            integer, intent(in) :: k
            type(error_t), allocatable, intent(out) :: error
            type(h5file_t) :: w
            integer :: js
            call w%open(path//'.resume', 'w', error); if (allocated(error)) return
            call w%write('/pressure_pa', c%state%p, error); if (allocated(error)) return
            call w%write('/gap_m', c%state%g, error); if (allocated(error)) return
            ! (a load path: the states a later case is compared with, the runs of each set)
            if (plan%path .and. size(seen) > 0) then
                call w%write('/seen_step', real(seen_step, dp), error); if (allocated(error)) return
                do js = 1, size(seen)     ! (an empty set as one empty run: no zero-sized dataset)
                    if (size(seen(js)%runs, 2) > 0) then
                        call w%write('/seen_'//str(js), real(seen(js)%runs, dp), error)
                    else
                        call w%write('/seen_'//str(js), reshape([0.0_dp, 0.0_dp], [2, 1]), error)
                    end if
                    if (allocated(error)) return
                end do
            end if
            ! (last: a file cut short holds no case, and is not used)
            call w%write('/case', int(k, i8), error); if (allocated(error)) return
            call w%close(error)
        end subroutine save_warm_start

        !> The warm start of case k + 1 after a resume: case k's pressure and gap when the file
        !> holds them, otherwise none (the chain continues from a cold start); on a load path
        !> (case k + 1 at place `step`) also the states kept for comparison
        subroutine restore_warm_start(k, step)
            integer, intent(in) :: k, step
            type(h5file_t) :: w
            type(error_t), allocatable :: e
            integer(i8) :: kr
            integer(i8) :: dims(7)
            integer :: rank_of, j
            logical :: is_double, ok
            real(dp), allocatable :: x(:, :)
            if (path_kind(path//'.resume') /= PATH_REGULAR) return
            call w%open(path//'.resume', 'r', e); if (allocated(e)) return
            call w%read_i0('/case', kr, e)
            if (.not. allocated(e) .and. kr == k) then
                allocate (p_prev(grid%nx, grid%ny), g_prev(grid%nx, grid%ny))
                call w%read_r2('/pressure_pa', p_prev, e)
                if (.not. allocated(e)) call w%read_r2('/gap_m', g_prev, e)
                if (allocated(e)) deallocate (p_prev, g_prev)
                if (.not. allocated(e) .and. plan%path .and. w%exists('/seen_step')) then
                    call w%shape_of('/seen_step', dims, rank_of, is_double)
                    ok = rank_of == 1 .and. is_double
                    if (ok) then
                        allocate (x(1, dims(1)))
                        call w%read_r2('/seen_step', x, e)
                        ok = .not. allocated(e)
                    end if
                    if (ok) then
                        seen_step = nint(x(1, :)); deallocate (seen); allocate (seen(size(seen_step)))
                        do j = 1, size(seen)
                            call w%shape_of('/seen_'//str(j), dims, rank_of, is_double)
                            ok = rank_of == 2 .and. is_double .and. dims(1) == 2
                            if (.not. ok) exit
                            deallocate (x); allocate (x(dims(1), dims(2)))
                            call w%read_r2('/seen_'//str(j), x, e)
                            ok = .not. allocated(e)
                            if (.not. ok) exit
                            seen(j)%runs = nint(x, i8)
                            ! (runs inside the grid: first cell from 1, last at most nx ny)
                            ok = all(seen(j)%runs(2, :) == 0 .or. (seen(j)%runs(1, :) >= 1 .and. seen(j)%runs(2, :) > 0 &
                                     .and. seen(j)%runs(1, :) + seen(j)%runs(2, :) - 1 <= int(grid%nx, i8)*grid%ny))
                            if (.not. ok) exit
                        end do
                    end if
                    ! (a file that does not hold them all as written: no comparison before this point)
                    if (.not. ok .or. any(seen_step >= step)) then
                        seen = [cell_set_t ::]; seen_step = [integer ::]
                    end if
                end if
            end if
            call w%close()
        end subroutine restore_warm_start

        !> Did case k, the last one written, converge?
        logical function converged_case(k) result(yes)
            integer, intent(in) :: k
            integer :: jc
            yes = .false.
            if (nrow == 0 .or. .not. allocated(columns)) return
            if (table(1, nrow) /= k) return
            jc = findloc(columns, 'converged', dim=1)
            yes = table(jc, nrow) == 1
        end function converged_case

        !> Did case k, the last one written, lose the contact (not converged, or no cell closed)?
        logical function separated(k) result(yes)
            integer, intent(in) :: k
            integer :: ja, jc
            yes = .false.
            if (nrow == 0 .or. .not. allocated(columns)) return
            if (table(1, nrow) /= k) return
            ja = findloc(columns, 'contact_area_fraction_cells', dim=1); jc = findloc(columns, 'converged', dim=1)
            yes = table(jc, nrow) /= 1 .or. cell(table, is_int, ja, nrow) <= 0.0_dp
        end function separated

        !> /cases/NNNNNN and the /summary row of case k (at place `step` of its chain)
        subroutine write_row(k, chain, speed, step, error)
            integer, intent(in) :: k
            type(study_chain_t), intent(in) :: chain
            real(dp), intent(in) :: speed
            integer, intent(in) :: step
            type(error_t), allocatable, intent(out) :: error
            character(len=16) :: tag
            character(len=:), allocatable :: names
            real(dp) :: values(7)
            integer :: j, np, nk, ja, jc
            write (tag, '("/cases/",i6.6)') k
            call write_case_group(f, trim(tag), c, error, r); if (allocated(error)) return
            np = plan%nparam
            values = [real(k, dp), real(chain%seed, dp), chain%eccentricity, chain%alpha_deg, chain%pressure_pa, &
                      speed, chain%temperature_c]
            call f%write(trim(tag)//'/parameters', values(1:np), error)
            if (allocated(error)) return
            names = trim(param_names(1))
            do j = 2, np
                names = names//', '//trim(param_names(j))
            end do
            call f%writeattr(trim(tag)//'/parameters', 'columns', names, error)
            if (allocated(error)) return
            ! every scalar of the case, except those that repeat a parameter column (speed_m_s,
            ! temperature_c)
            if (.not. allocated(keep)) &
                keep = pack([(j, j = 1, r%n)], [(all(r%scalars(j)%name /= param_names(1:np)), j = 1, r%n)])
            nk = np + size(keep)
            if (.not. allocated(table)) then
                ! a load path's seven columns last: the case's place on its path, its event, the
                ! patches made and lost since the path's previous case with their cells, and how
                ! many of those are bistable
                j = nk + merge(7, 0, plan%path)
                allocate (columns(j), units(j), is_int(j))
                allocate (table(j, nmine))
                columns(1:np) = param_names(1:np); units(1:np) = param_units(1:np)
                is_int(1:np) = .false.; is_int(1:2) = .true.
                do j = 1, size(keep)
                    columns(np + j) = r%scalars(keep(j))%name; units(np + j) = r%scalars(keep(j))%units
                    is_int(np + j) = r%scalars(keep(j))%is_integer
                end do
                if (plan%path) then
                    columns(nk + 1:nk + 7) = path_columns
                    units(nk + 1:nk + 7) = '-'; is_int(nk + 1:nk + 7) = .true.
                end if
            end if
            ! the event since the path's previous case (the last row written, when it is k - 1)
            jump_now = 0
            if (plan%path .and. step > 1 .and. nrow > 0) then
                if (table(1, nrow) == k - 1) then
                    ja = findloc(columns, 'contact_area_fraction_cells', dim=1)
                    jc = findloc(columns, 'converged', dim=1)
                    jump_now = path_jump(table(jc, nrow) == 1, cell(table, is_int, ja, nrow), c%state%converged, &
                                         r%get('contact_area_fraction_cells'))
                end if
            end if
            nrow = nrow + 1
            table(1:np, nrow) = [int(k, i8), chain%seed, transfer(values(3:np), 0_i8, np - 2)]
            do j = 1, size(keep)
                if (r%scalars(keep(j))%is_integer) then
                    table(np + j, nrow) = nint(r%scalars(keep(j))%value, i8)
                else
                    table(np + j, nrow) = transfer(r%scalars(keep(j))%value, 0_i8)
                end if
            end do
            if (plan%path) table(nk + 1:nk + 7, nrow) = [int(step, i8), int(jump_now, i8), int(patches, i8), patch_cells, &
                                                         int(bistable, i8)]
            call f%append_row('/summary', columns, units, is_int, table(:, nrow), error); if (allocated(error)) return
            if (.not. f%attr_exists('/summary', 'parameters')) then     ! (the first row made the table)
                call f%writeattr('/summary', 'parameters', param_names(1:np), error); if (allocated(error)) return
            end if
            call f%flush(error)
        end subroutine write_row

    end subroutine run_study

    !> The event between consecutive cases of a load path, from their convergence and contact area
    !> fraction (closed cells): JUMP_IN where the contact is made (from none, or after a case that
    !> did not converge) or becomes full; JUMP_OUT where it is lost (to none, or to a case that did
    !> not converge) or leaves full contact; 0 otherwise
    pure integer function path_jump(conv0, area0, conv1, area1) result(jump)
        logical, intent(in) :: conv0, conv1
        real(dp), intent(in) :: area0, area1
        logical :: in0, in1
        jump = 0
        in0 = conv0 .and. area0 > 0.0_dp; in1 = conv1 .and. area1 > 0.0_dp
        if (in0 .and. .not. in1) then
            jump = JUMP_OUT
        else if (in1 .and. .not. in0) then
            jump = JUMP_IN
        else if (in0 .and. in1) then
            if (area0 < 1.0_dp .and. area1 >= 1.0_dp) jump = JUMP_IN
            if (area0 >= 1.0_dp .and. area1 < 1.0_dp) jump = JUMP_OUT
        end if
    end function path_jump

    !> /paths, a row per load path of the complete /summary `table` (rows in case order): the
    !> path's seed, spectrum, speed (and temperature), its cases, the jumps flagged along it, the
    !> first case after a jump-in and its load, the patches made and lost along it, and the
    !> pull-off: under load control the most tensile load carried just before the contact was lost
    !> (the last case before separation),
    !> under approach control the most tensile load at a minimum of the load along the path (both
    !> neighbours carry more); case 0 and NaN where the path shows none. The attribute `control`
    !> says which ('load' or 'approach').
    subroutine write_paths(f, columns, units, is_int, table, plan, error)
        type(h5file_t), intent(inout) :: f
        character(len=*), intent(in) :: columns(:), units(:)
        logical, intent(in) :: is_int(:)
        integer(i8), intent(in) :: table(:, :)
        type(study_plan_t), intent(in) :: plan
        type(error_t), allocatable, intent(out) :: error
        character(len=64), allocatable :: pcols(:), punits(:)
        logical, allocatable :: pint(:)
        integer(i8), allocatable :: e(:, :)
        real(dp) :: load(plan%nstep), area(plan%nstep), pull
        integer :: jump(plan%nstep)
        integer(i8) :: made(plan%nstep), lost(plan%nstep), bist(plan%nstep)
        logical :: conv(plan%nstep)
        integer :: ic, n, s, k0, jm, jc, jj, ja, ipull, ijin, nt, jpm, jpl, jpb
        if (size(table, 2) /= plan%ncase .or. size(units) /= size(columns)) then
            call fatal_error(error, "veslide:study:write_paths: the table is not the complete study"); return
        end if
        jm = findloc(columns, 'mean_pressure_pa', dim=1); jc = findloc(columns, 'converged', dim=1)
        jj = findloc(columns, 'path_jump', dim=1); ja = findloc(columns, 'contact_area_fraction_cells', dim=1)
        jpm = findloc(columns, 'path_patches_made', dim=1); jpl = findloc(columns, 'path_patches_lost', dim=1)
        jpb = findloc(columns, 'path_patches_bistable', dim=1)
        if (min(jm, jc, jj, ja, jpm, jpl, jpb) == 0) then
            call fatal_error(error, "veslide:study:write_paths: /summary lacks a column of the load path"); return
        end if
        nt = merge(1, 0, plan%nparam == 7)
        pcols = [character(len=64) :: 'seed', 'eccentricity', 'alpha_deg', 'speed_m_s']
        punits = [character(len=64) :: '-', '-', 'degree', 'm/s']
        if (nt == 1) then
            pcols = [character(len=64) :: pcols, 'temperature_c']; punits = [character(len=64) :: punits, 'degC']
        end if
        pcols = [character(len=64) :: pcols, 'first_case', 'last_case', 'n_jump_in', 'n_jump_out', 'jump_in_case', &
                 'jump_in_pa', 'pull_off_case', 'pull_off_pa', 'n_patches_made', 'n_patches_lost', &
                 'n_patches_bistable']
        punits = [character(len=64) :: punits, '-', '-', '-', '-', '-', 'Pa', '-', 'Pa', '-', '-', '-']
        pint = [.true., .false., .false., .false., [(.false., s = 1, nt)], .true., .true., .true., .true., .true., &
                .false., .true., .false., .true., .true., .true.]
        n = plan%nstep
        allocate (e(size(pcols), size(plan%chains)))
        do ic = 1, size(plan%chains)
            associate (chain => plan%chains(ic))
                k0 = chain%first_case
                do s = 1, n
                    load(s) = cell(table, is_int, jm, k0 + s - 1); area(s) = cell(table, is_int, ja, k0 + s - 1)
                    conv(s) = table(jc, k0 + s - 1) == 1; jump(s) = int(table(jj, k0 + s - 1))
                    made(s) = table(jpm, k0 + s - 1); lost(s) = table(jpl, k0 + s - 1)
                    bist(s) = table(jpb, k0 + s - 1)
                end do
                ijin = findloc(jump, JUMP_IN, dim=1)
                ipull = 0; pull = huge(1.0_dp)
                do s = 2, n
                    if (plan%approach) then
                        if (s == n) exit
                        if (.not. all(conv(s - 1:s + 1))) cycle
                        if (load(s) <= load(s - 1) .and. load(s) <= load(s + 1) .and. load(s) < pull) then
                            ipull = s; pull = load(s)
                        end if
                    else if (jump(s) == JUMP_OUT .and. (.not. conv(s) .or. area(s) <= 0.0_dp)) then
                        if (load(s - 1) < pull) then
                            ipull = s - 1; pull = load(s - 1)
                        end if
                    end if
                end do
                e(1:4, ic) = [chain%seed, transfer([chain%eccentricity, chain%alpha_deg, &
                              plan%speeds(chain%speed_index)], 0_i8, 3)]
                if (nt == 1) e(5, ic) = transfer(chain%temperature_c, 0_i8)
                e(5 + nt:, ic) = [int(k0, i8), int(k0 + n - 1, i8), int(count(jump == JUMP_IN), i8), &
                                  int(count(jump == JUMP_OUT), i8), &
                                  merge(int(k0 + ijin - 1, i8), 0_i8, ijin > 0), &
                                  transfer(merge(load(max(ijin, 1)), nan(), ijin > 0), 0_i8), &
                                  merge(int(k0 + ipull - 1, i8), 0_i8, ipull > 0), &
                                  transfer(merge(pull, nan(), ipull > 0), 0_i8), sum(made), sum(lost), sum(bist)]
            end associate
        end do
        call f%write_table('/paths', pcols, punits, pint, e, error); if (allocated(error)) return
        call f%writeattr('/paths', 'control', trim(merge('approach', 'load    ', plan%approach)), error)
    contains
        real(dp) function nan()
            nan = ieee_value(0.0_dp, ieee_quiet_nan)
        end function nan
    end subroutine write_paths

    !> The value of cell (j, i) of a table as a real
    pure real(dp) function cell(bits, is_int, j, i) result(x)
        integer(i8), intent(in) :: bits(:, :)
        logical, intent(in) :: is_int(:)
        integer, intent(in) :: j, i
        if (is_int(j)) then
            x = real(bits(j, i), dp)
        else
            x = transfer(bits(j, i), 0.0_dp)
        end if
    end function cell

    !> /ensemble from the complete /summary table (rows in case order, seed-major, so row r of
    !> seed s is r + (s - 1) m): per combination of the other parameters, n_seeds and the mean
    !> and standard error over seeds of every scalar
    subroutine write_ensemble(f, columns, units, is_int, table, nseed, error)
        type(h5file_t), intent(inout) :: f
        character(len=*), intent(in) :: columns(:), units(:)
        logical, intent(in) :: is_int(:)
        integer(i8), intent(in) :: table(:, :)
        integer, intent(in) :: nseed
        type(error_t), allocatable, intent(out) :: error
        character(len=64), allocatable :: ecols(:), eunits(:)
        logical, allocatable :: eint(:)
        integer(i8), allocatable :: e(:, :)
        real(dp) :: x(nseed), mean, sem
        integer :: m, r, j, ncol, nv, kk, np, ne
        ncol = size(columns); m = size(table, 2)/nseed
        ! the parameter columns lead (param_names; temperature_c the 7th when present)
        np = 6
        if (ncol >= 7) then
            if (trim(columns(7)) == param_names(7)) np = 7
        end if
        nv = ncol - np; ne = np - 2          ! the parameters but case and seed, then n_seeds
        allocate (ecols(ne + 1 + 2*nv), eunits(ne + 1 + 2*nv), eint(ne + 1 + 2*nv), e(ne + 1 + 2*nv, m))
        ecols(1:ne) = param_names(3:np); eunits(1:ne) = param_units(3:np); eint(1:ne) = .false.
        ecols(ne + 1) = 'n_seeds'; eunits(ne + 1) = '-'; eint(ne + 1) = .true.
        eint(ne + 2:) = .false.
        do j = 1, nv
            ecols(ne + 1 + j) = 'mean_'//trim(columns(np + j)); eunits(ne + 1 + j) = units(np + j)
            ecols(ne + 1 + nv + j) = 'sem_'//trim(columns(np + j)); eunits(ne + 1 + nv + j) = units(np + j)
        end do
        do r = 1, m
            e(1:ne, r) = table(3:np, r)
            e(ne + 1, r) = nseed
            do j = 1, nv
                x = [(cell(table, is_int, np + j, r + (kk - 1)*m), kk = 1, nseed)]
                call seed_statistics(x, axial_of(trim(columns(np + j))), mean, sem)
                e(ne + 1 + j, r) = transfer(mean, 0_i8); e(ne + 1 + nv + j, r) = transfer(sem, 0_i8)
            end do
        end do
        call f%write_table('/ensemble', ecols, eunits, eint, e, error); if (allocated(error)) return
        call f%writeattr('/ensemble', 'parameters', param_names(3:np), error)
    end subroutine write_ensemble

    !> Mean and standard error of the mean over seeds. Axial data (angles modulo pi, `axial`
    !> AXIAL_HALF_TURN for [0, pi) or AXIAL_SYMMETRIC for (-pi/2, pi/2]) use the circular mean of
    !> the doubled angle, atan2(<sin 2x>, <cos 2x>)/2, in the range of the quantity, and deviations
    !> wrapped into (-pi/2, pi/2]: an axis scattering about 0 = pi averages to 0, not to pi/2.
    pure subroutine seed_statistics(x, axial, mean, sem)
        real(dp), intent(in) :: x(:)
        integer, intent(in) :: axial
        real(dp), intent(out) :: mean, sem
        real(dp) :: d(size(x))
        integer :: n
        n = size(x)
        if (axial /= AXIAL_NONE) then
            mean = 0.5_dp*atan2(sum(sin(2*x)), sum(cos(2*x)))      ! in (-pi/2, pi/2]
            if (axial == AXIAL_HALF_TURN) mean = modulo(mean, pi)
            d = x - mean
            d = d - pi*anint(d/pi)
        else
            mean = sum(x)/n
            d = x - mean
        end if
        sem = sqrt(sum(d**2)/max(1, n - 1))/sqrt(real(n, dp))
    end subroutine seed_statistics

    !> Join the rank files `parts` of a distributed study of `cfg` into the (temporary) file `path`:
    !> provenance, every /cases group, /summary in case order and /ensemble, as a serial study
    !> writes them. Every case of the plan must be present exactly once.
    subroutine merge_study_parts(cfg, path, parts, error)
        type(config_t), intent(in) :: cfg
        character(len=*), intent(in) :: path, parts(:)
        type(error_t), allocatable, intent(out) :: error
        type(study_plan_t) :: plan
        type(h5file_t) :: f, src
        character(len=64), allocatable :: columns(:), pcols(:), units(:)
        logical, allocatable :: is_int(:), pint(:)
        integer(i8), allocatable :: table(:, :), rows(:, :)
        integer :: k, i, ncol, kcase, first_part
        logical, allocatable :: seen(:)
        character(len=16) :: tag
        call plan_study(cfg, plan)
        allocate (seen(plan%ncase)); seen = .false.
        call f%open(path, 'w', error); if (allocated(error)) return
        call write_provenance(f, cfg%path, cfg%text, plan%seeds, error, study=.true., &
                                  preparation=cfg%surface%preparation); if (allocated(error)) return
        call write_warnings(f, '', cfg%warnings, error); if (allocated(error)) return
        do k = 1, size(parts)
            call src%open(trim(parts(k)), 'r', error); if (allocated(error)) return
            if (.not. src%exists('/summary')) then       ! a rank with no chain (more ranks than chains)
                call src%close(); cycle
            end if
            call src%read_table('/summary', pcols, pint, rows, error)
            if (allocated(error)) return
            if (.not. allocated(table)) then
                first_part = k
                ncol = size(pcols)
                columns = pcols; is_int = pint
                allocate (table(ncol, plan%ncase))
            else if (size(pcols) /= ncol) then
                call fatal_error(error, "veslide:study:merge: "//trim(parts(k))//" has other columns than "// &
                                 trim(parts(1))); return
            end if
            do i = 1, size(rows, 2)
                kcase = int(rows(1, i))
                write (tag, '("/cases/",i6.6)') kcase
                if (kcase < 1 .or. kcase > plan%ncase) then
                    call fatal_error(error, "veslide:study:merge: "//trim(parts(k))//" holds a case outside the study")
                    return
                end if
                if (seen(kcase)) then
                    call fatal_error(error, "veslide:study:merge: "//trim(tag)//" appears in two parts"); return
                end if
                seen(kcase) = .true.
                table(:, kcase) = rows(:, i)
                call f%copy_from(src, trim(tag), trim(tag), error); if (allocated(error)) return
            end do
            call src%close()
        end do
        if (.not. all(seen)) then
            call fatal_error(error, "veslide:study:merge: the parts lack some cases of the study"); return
        end if
        call units_of(columns, units)
        call f%write_table('/summary', columns, units, is_int, table, error); if (allocated(error)) return
        call f%writeattr('/summary', 'parameters', param_names(1:plan%nparam), error); if (allocated(error)) return
        if (size(plan%seeds) > 1) then
            call write_ensemble(f, columns, units, is_int, table, size(plan%seeds), error)
            if (allocated(error)) return
        end if
        if (plan%path) then
            call write_paths(f, columns, units, is_int, table, plan, error); if (allocated(error)) return
        end if
        call f%close(error)

    contains

        !> The units attribute of the first part's /summary
        subroutine units_of(columns, units)
            character(len=64), intent(in) :: columns(:)
            character(len=64), allocatable, intent(out) :: units(:)
            allocate (units(size(columns)))
            units = '-'
            call src%open(trim(parts(first_part)), 'r', error); if (allocated(error)) return
            call src%read_attr_text_list('/summary', 'units', units, error)
            call src%close()
        end subroutine units_of

    end subroutine merge_study_parts

end module veslide_study
