!> &material: the solid (elastic, the paper's one-term law, creep or relaxation Prony series)
module veslide_config_material
    use veslide_kinds, only: dp
    use veslide_error, only: error_t, fatal_error
    use veslide_strings, only: str
    use veslide_config_common, only: group_text_t, diagnose_read, read_failed, split_lines, require, choices_text, is_one_of, &
                                     finite_in, max_terms, unset_real, list_length, check_list, check_text_length, &
                                     max_text, is_unset, assigned_names
    use veslide_material, only: material_model_names, shift_names, base_names
    implicit none
    private
    public :: material_config_t, read_material_config

    type :: material_config_t
        character(len=:), allocatable :: model           !! one of material_model_names
        real(dp) :: young_pa = 1.0e7_dp                  !! elastic: Young's modulus [Pa]
        real(dp) :: poisson = 0.5_dp                     !! Poisson ratio, all models
        real(dp) :: einf_pa = 1.0e8_dp                   !! one_term: glassy modulus [Pa]
        real(dp) :: ratio = 11.0_dp                      !! one_term: Einf/E0
        real(dp) :: tau_s = 1.0e-2_dp                    !! one_term: retardation time [s]
        real(dp) :: e0_pa = 0.0_dp                       !! creep, relaxation: relaxed modulus [Pa]
        real(dp), allocatable :: prony_coef(:)           !! c_k [1/Pa] (creep) or e_j [Pa] (relaxation)
        real(dp), allocatable :: prony_time_s(:)         !! tau_k or rho_j [s]
        !> time-temperature superposition: the times above are the master curve's at the
        !> reference temperature; at `temperature_c` each is multiplied by the shift factor a_T
        !> (`shift`: 'none', 'wlf', 'arrhenius' or 'table'; veslide_material's shift_factor)
        character(len=:), allocatable :: shift
        real(dp) :: temperature_c = 0.0_dp, reference_temperature_c = 0.0_dp
        real(dp) :: wlf_c1 = 0.0_dp, wlf_c2_k = 0.0_dp, activation_energy_j_mol = 0.0_dp
        !> shift = 'table': measured shift factors, log10 a_T at temperatures [C] (strictly
        !> increasing temperatures, strictly decreasing log10 a_T; empty for the other laws)
        real(dp), allocatable :: shift_table_c(:), shift_table_log10(:)
        !> a layer of this thickness on a rigid base [m] (0: a half-space), resting on it as `base`
        real(dp) :: thickness_m = 0.0_dp
        character(len=:), allocatable :: base
        character(len=:), allocatable :: given(:)        !! the variables the input assigned
    end type material_config_t

    character(len=*), parameter :: names(21) = [character(len=23) :: 'model', 'young_pa', 'poisson', 'einf_pa', &
        'ratio', 'tau_s', 'e0_pa', 'creep_c_per_pa', 'creep_tau_s', 'relax_e_pa', 'relax_rho_s', 'shift', &
        'temperature_c', 'reference_temperature_c', 'wlf_c1', 'wlf_c2_k', 'activation_energy_j_mol', 'thickness_m', &
        'base', 'shift_temperatures_c', 'shift_log10_at']
    character(len=*), parameter :: list256 = 'a list of up to 256 real numbers'
    character(len=*), parameter :: kinds(21) = [character(len=40) :: "a quoted text ('one_term')", &
        'a real number', 'a real number', 'a real number', 'a real number', 'a real number', 'a real number', &
        list256, list256, list256, list256, &
        "a quoted text ('wlf')", 'a real number', 'a real number', 'a real number', 'a real number', &
        'a real number', 'a real number', "a quoted text ('bonded')", list256, list256]
    !> Largest modulus accepted [Pa]: beyond it double precision loses the physics
    real(dp), parameter :: max_modulus = 1.0e15_dp
    !> Longest time accepted [s] (also after the shift to a temperature): the kernel takes w tau
    !> with w = |q.v| below 1e27 rad/s for any grid and speed the input accepts, so up to 1e200 s
    !> every product stays finite (and far from overflow) in double precision. A master curve
    !> over 40 decades at a reference at its data's coldest end needs about 1e40 s.
    real(dp), parameter, public :: max_time = 1.0e200_dp
    character(len=*), parameter :: time_range = "> 0 and <= 1e200 [s]"
    !> No solid is softer than about 10 Pa (the softest hydrogels): a modulus below 1 Pa is a
    !> modulus in kPa or MPa read as Pa, refused with that hint
    real(dp), parameter :: min_modulus = 1.0_dp
    character(len=*), parameter :: modulus_range = "1 to 1e15 [Pa]; no solid is softer than about 10 Pa:"// &
                                                   " a modulus in kPa or MPa read as Pa?"

contains

    !> Read &material from its text (absent: defaults) and check it
    subroutine read_material_config(self, g, path, error)
        type(material_config_t), intent(out) :: self
        type(group_text_t), intent(in) :: g
        character(len=*), intent(in) :: path
        type(error_t), allocatable, intent(out) :: error
        character(len=max_text + 1) :: model, shift, base
        real(dp) :: young_pa, poisson, einf_pa, ratio, tau_s, e0_pa
        real(dp) :: creep_c_per_pa(max_terms), creep_tau_s(max_terms), relax_e_pa(max_terms), relax_rho_s(max_terms)
        real(dp) :: temperature_c, reference_temperature_c, wlf_c1, wlf_c2_k, activation_energy_j_mol, thickness_m
        real(dp) :: shift_temperatures_c(max_terms), shift_log10_at(max_terms)
        integer :: stat
        character(len=512) :: msg
        character(len=:), allocatable :: lines(:)
        namelist /material/ model, young_pa, poisson, einf_pa, ratio, tau_s, e0_pa, creep_c_per_pa, creep_tau_s, &
            relax_e_pa, relax_rho_s, shift, temperature_c, reference_temperature_c, wlf_c1, wlf_c2_k, &
            activation_energy_j_mol, thickness_m, base, shift_temperatures_c, shift_log10_at
        thickness_m = 0.0_dp; base = 'bonded'
        shift_temperatures_c = unset_real(); shift_log10_at = unset_real()
        shift = 'none'; temperature_c = unset_real(); reference_temperature_c = unset_real()
        wlf_c1 = unset_real(); wlf_c2_k = unset_real(); activation_energy_j_mol = unset_real()
        model = 'elastic'; young_pa = self%young_pa; poisson = self%poisson; einf_pa = self%einf_pa
        ratio = self%ratio; tau_s = self%tau_s; e0_pa = self%e0_pa
        creep_c_per_pa = unset_real(); creep_tau_s = unset_real(); relax_e_pa = unset_real()
        relax_rho_s = unset_real()
        call split_lines(g%text, lines)
        read (lines, nml=material, iostat=stat, iomsg=msg)
        if (read_failed(stat)) then
            call diagnose_read(stat, msg, path, 'material', g%body, names, kinds, try, error); return
        end if
        call check_text_length(error, model, path, 'material', 'model', g%body)
        call check_text_length(error, shift, path, 'material', 'shift', g%body)
        call check_text_length(error, base, path, 'material', 'base', g%body); if (allocated(error)) return
        self%thickness_m = thickness_m; self%base = trim(base)
        call require(error, thickness_m == 0.0_dp .or. finite_in(thickness_m, 1.0e-12_dp, 1.0e3_dp), path, &
                     'material', 'thickness_m', str(thickness_m), "0 (a half-space) or 1e-12 to 1e3 [m]")
        call require(error, is_one_of(self%base, base_names), path, 'material', 'base', "'"//self%base//"'", &
                     choices_text(base_names))
        if (allocated(error)) return
        call read_shift(); if (allocated(error)) return
        self%model = trim(model); self%young_pa = young_pa; self%poisson = poisson; self%einf_pa = einf_pa
        self%ratio = ratio; self%tau_s = tau_s; self%e0_pa = e0_pa
        call assigned_names(g%body, self%given)
        call check_list(error, creep_c_per_pa, path, 'material', 'creep_c_per_pa')
        call check_list(error, creep_tau_s, path, 'material', 'creep_tau_s')
        call check_list(error, relax_e_pa, path, 'material', 'relax_e_pa')
        call check_list(error, relax_rho_s, path, 'material', 'relax_rho_s')
        if (allocated(error)) return
        select case (self%model)
        case ('creep')
            call take_series('creep_c_per_pa', creep_c_per_pa, 'creep_tau_s', creep_tau_s)
        case ('relaxation')
            call take_series('relax_e_pa', relax_e_pa, 'relax_rho_s', relax_rho_s)
        case default
            allocate (self%prony_coef(0), self%prony_time_s(0))
        end select
        if (allocated(error)) return

        call require(error, finite_in(poisson, 0.0_dp, 0.5_dp), path, 'material', 'poisson', str(poisson), "0 to 0.5")
        call require(error, is_one_of(self%model, material_model_names), path, 'material', 'model', &
                     "'"//self%model//"'", choices_text(material_model_names))
        if (allocated(error)) return
        select case (self%model)
        case ('elastic')
            call require(error, finite_in(young_pa, min_modulus, max_modulus), path, 'material', &
                         'young_pa', str(young_pa), modulus_range)
        case ('one_term')
            call require(error, finite_in(einf_pa, min_modulus, max_modulus), path, 'material', &
                         'einf_pa', str(einf_pa), modulus_range)
            call require(error, finite_in(ratio, 1.0_dp, 1.0e12_dp, open_low=.true.), path, 'material', 'ratio', &
                         str(ratio), "> 1 and <= 1e12 (Einf/E0)")
            if (.not. allocated(error)) &
                call require(error, einf_pa/ratio >= min_modulus, path, 'material', 'ratio', str(ratio), &
                             "at most einf_pa/1 Pa = "//str(einf_pa/min_modulus)//" (E0 = einf_pa/ratio = "// &
                             str(einf_pa/ratio)//" Pa; no solid is softer than about 10 Pa)")
            call require(error, finite_in(tau_s, 0.0_dp, max_time, open_low=.true.), path, 'material', 'tau_s', &
                         str(tau_s), time_range)
        case ('creep', 'relaxation')
            call require(error, finite_in(e0_pa, min_modulus, max_modulus), path, 'material', 'e0_pa', &
                         str(e0_pa), modulus_range)
            call check_terms(); if (allocated(error)) return
            if (self%model == 'creep') &
                call require(error, sum(self%prony_coef) < 1.0_dp/e0_pa, path, 'material', 'creep_c_per_pa', &
                             "sum "//str(sum(self%prony_coef)), &
                             "sum below 1/e0_pa = "//str(1.0_dp/e0_pa)//" (so that Einf > E0)")
        end select

    contains

        !> The temperature shift: its law's constants required and in range, the test temperature
        !> the reference's when not given
        subroutine read_shift()
            self%shift = trim(shift)
            allocate (self%shift_table_c(0), self%shift_table_log10(0))
            call require(error, is_one_of(self%shift, shift_names), path, 'material', 'shift', "'"//self%shift//"'", &
                         choices_text(shift_names))
            if (.not. allocated(error) .and. self%shift /= 'table') then
                call unused_list(shift_temperatures_c, 'shift_temperatures_c')
                call unused_list(shift_log10_at, 'shift_log10_at')
            end if
            if (allocated(error) .or. self%shift == 'none') then
                if (.not. allocated(error)) call unused(temperature_c, 'temperature_c')
                if (.not. allocated(error)) call unused(reference_temperature_c, 'reference_temperature_c')
                if (.not. allocated(error)) call unused(wlf_c1, 'wlf_c1')
                if (.not. allocated(error)) call unused(wlf_c2_k, 'wlf_c2_k')
                if (.not. allocated(error)) call unused(activation_energy_j_mol, 'activation_energy_j_mol')
                return
            end if
            call given(reference_temperature_c, 'reference_temperature_c'); if (allocated(error)) return
            if (is_unset(temperature_c)) temperature_c = reference_temperature_c
            call require(error, finite_in(reference_temperature_c, -273.15_dp, 1.0e4_dp, open_low=.true.), path, &
                         'material', 'reference_temperature_c', str(reference_temperature_c), "> -273.15 [C]")
            call require(error, finite_in(temperature_c, -273.15_dp, 1.0e4_dp, open_low=.true.), path, &
                         'material', 'temperature_c', str(temperature_c), "> -273.15 [C]")
            if (allocated(error)) return
            self%temperature_c = temperature_c; self%reference_temperature_c = reference_temperature_c
            select case (self%shift)
            case ('wlf')
                call given(wlf_c1, 'wlf_c1'); call given(wlf_c2_k, 'wlf_c2_k'); if (allocated(error)) return
                call unused(activation_energy_j_mol, 'activation_energy_j_mol'); if (allocated(error)) return
                call require(error, finite_in(wlf_c1, 0.0_dp, 1.0e3_dp, open_low=.true.), path, 'material', &
                             'wlf_c1', str(wlf_c1), "> 0 and <= 1e3")
                call require(error, finite_in(wlf_c2_k, 0.0_dp, 1.0e4_dp, open_low=.true.), path, 'material', &
                             'wlf_c2_k', str(wlf_c2_k), "> 0 and <= 1e4 [K]")
                call require(error, temperature_c - reference_temperature_c > -wlf_c2_k, path, 'material', &
                             'temperature_c', str(temperature_c), "above reference_temperature_c - wlf_c2_k = "// &
                             str(reference_temperature_c - wlf_c2_k)//" (where the WLF law diverges)")
                self%wlf_c1 = wlf_c1; self%wlf_c2_k = wlf_c2_k
            case ('arrhenius')
                call given(activation_energy_j_mol, 'activation_energy_j_mol'); if (allocated(error)) return
                call unused(wlf_c1, 'wlf_c1'); call unused(wlf_c2_k, 'wlf_c2_k'); if (allocated(error)) return
                call require(error, finite_in(activation_energy_j_mol, 0.0_dp, 1.0e7_dp, open_low=.true.), path, &
                             'material', 'activation_energy_j_mol', str(activation_energy_j_mol), "> 0 and <= 1e7 [J/mol]")
                self%activation_energy_j_mol = activation_energy_j_mol
            case ('table')
                call unused(wlf_c1, 'wlf_c1'); call unused(wlf_c2_k, 'wlf_c2_k')
                call unused(activation_energy_j_mol, 'activation_energy_j_mol'); if (allocated(error)) return
                call read_table(); if (allocated(error)) return
                call in_table(reference_temperature_c, 'reference_temperature_c')
                call in_table(temperature_c, 'temperature_c')
            end select
        end subroutine read_shift

        !> The measured shift factors: 2 to max_terms points, temperatures strictly increasing
        !> and above 0 K, log10 a_T finite, within +-300 (a_T a double) and strictly decreasing:
        !> every relaxation of a thermorheologically simple solid is faster when it is warmer
        subroutine read_table()
            integer :: nt, na, k
            call check_list(error, shift_temperatures_c, path, 'material', 'shift_temperatures_c')
            call check_list(error, shift_log10_at, path, 'material', 'shift_log10_at')
            if (allocated(error)) return
            nt = list_length(shift_temperatures_c); na = list_length(shift_log10_at)
            if (nt < 2 .or. nt /= na) then
                call fatal_error(error, "veslide: "//path//": &material shift_temperatures_c and shift_log10_at"// &
                    " must list the same number (2 to "//str(max_terms)//") of points with shift = 'table', got "// &
                    str(nt)//" and "//str(na)); return
            end if
            do k = 1, nt
                call require(error, finite_in(shift_temperatures_c(k), -273.15_dp, 1.0e4_dp, open_low=.true.), &
                             path, 'material', 'shift_temperatures_c('//str(k)//')', str(shift_temperatures_c(k)), &
                             "> -273.15 [C]")
                call require(error, finite_in(shift_log10_at(k), -300.0_dp, 300.0_dp), path, 'material', &
                             'shift_log10_at('//str(k)//')', str(shift_log10_at(k)), "-300 to 300 (log10 of a_T)")
                if (k == 1 .or. allocated(error)) cycle
                call require(error, shift_temperatures_c(k) > shift_temperatures_c(k - 1), path, 'material', &
                             'shift_temperatures_c('//str(k)//')', str(shift_temperatures_c(k)), &
                             "above shift_temperatures_c("//str(k - 1)//") = "//str(shift_temperatures_c(k - 1))// &
                             ": temperatures strictly increasing")
                call require(error, shift_log10_at(k) < shift_log10_at(k - 1), path, 'material', &
                             'shift_log10_at('//str(k)//')', str(shift_log10_at(k)), &
                             "below shift_log10_at("//str(k - 1)//") = "//str(shift_log10_at(k - 1))// &
                             ": a_T falls as the temperature rises (every relaxation is faster when warmer)")
            end do
            if (allocated(error)) return
            self%shift_table_c = shift_temperatures_c(1:nt); self%shift_table_log10 = shift_log10_at(1:nt)
        end subroutine read_table

        !> A temperature of the material within the shift table (measured shift factors are not
        !> extrapolated)
        subroutine in_table(t, name)
            real(dp), intent(in) :: t
            character(len=*), intent(in) :: name
            if (allocated(error)) return
            call require(error, t >= self%shift_table_c(1) .and. t <= self%shift_table_c(size(self%shift_table_c)), &
                         path, 'material', name, str(t), "within the shift table, shift_temperatures_c = "// &
                         str(self%shift_table_c(1))//" to "//str(self%shift_table_c(size(self%shift_table_c)))// &
                         " [C]: measured shift factors are not extrapolated")
        end subroutine in_table

        subroutine unused_list(x, name)
            real(dp), intent(in) :: x(:)
            character(len=*), intent(in) :: name
            if (allocated(error)) return
            if (list_length(x) > 0) call fatal_error(error, "veslide: "//path//": &material "//name// &
                                                     " has no use with shift = '"//self%shift//"'")
        end subroutine unused_list

        subroutine given(x, name)
            real(dp), intent(in) :: x
            character(len=*), intent(in) :: name
            if (allocated(error)) return
            if (is_unset(x)) call fatal_error(error, "veslide: "//path//": &material "//name//" is needed with"// &
                                              " shift = '"//self%shift//"'")
        end subroutine given

        subroutine unused(x, name)
            real(dp), intent(in) :: x
            character(len=*), intent(in) :: name
            if (allocated(error)) return
            if (.not. is_unset(x)) call fatal_error(error, "veslide: "//path//": &material "//name// &
                                                    " has no use with shift = '"//self%shift//"'")
        end subroutine unused

        subroutine take_series(name_c, c, name_t, t)
            character(len=*), intent(in) :: name_c, name_t
            real(dp), intent(in) :: c(:), t(:)
            integer :: nc, nt
            nc = list_length(c); nt = list_length(t)
            if (nc == 0 .or. nc /= nt) then
                call fatal_error(error, "veslide: "//path//": &material "//name_c//" and "//name_t// &
                    " must list the same number (1 to "//str(max_terms)//") of terms, got "//str(nc)//" and "// &
                    str(nt)); return
            end if
            self%prony_coef = c(1:nc); self%prony_time_s = t(1:nt)
        end subroutine take_series

        !> Every Prony term positive and finite, named by its list and index
        subroutine check_terms()
            integer :: k
            character(len=:), allocatable :: cn, tn
            cn = merge('creep_c_per_pa', 'relax_e_pa    ', self%model == 'creep')
            tn = merge('creep_tau_s', 'relax_rho_s', self%model == 'creep')
            do k = 1, size(self%prony_coef)
                call require(error, finite_in(self%prony_coef(k), 0.0_dp, max_modulus, open_low=.true.), path, &
                             'material', trim(cn)//"("//str(k)//")", str(self%prony_coef(k)), "> 0 and finite")
                call require(error, finite_in(self%prony_time_s(k), 0.0_dp, max_time, open_low=.true.), path, &
                             'material', tn//"("//str(k)//")", str(self%prony_time_s(k)), time_range)
            end do
        end subroutine check_terms

        subroutine try(lines, stat, msg)
            character(len=*), intent(in) :: lines(:)
            integer, intent(out) :: stat
            character(len=*), intent(out) :: msg
            character(len=max_text + 1) :: model, shift, base
            real(dp) :: young_pa, poisson, einf_pa, ratio, tau_s, e0_pa
            real(dp) :: creep_c_per_pa(max_terms), creep_tau_s(max_terms), relax_e_pa(max_terms), &
                        relax_rho_s(max_terms), shift_temperatures_c(max_terms), shift_log10_at(max_terms)
            real(dp) :: temperature_c, reference_temperature_c, wlf_c1, wlf_c2_k, activation_energy_j_mol, thickness_m
            namelist /material/ model, young_pa, poisson, einf_pa, ratio, tau_s, e0_pa, creep_c_per_pa, &
                creep_tau_s, relax_e_pa, relax_rho_s, shift, temperature_c, reference_temperature_c, wlf_c1, &
                wlf_c2_k, activation_energy_j_mol, thickness_m, base, shift_temperatures_c, shift_log10_at
            read (lines, nml=material, iostat=stat, iomsg=msg)
        end subroutine try

    end subroutine read_material_config

end module veslide_config_material
