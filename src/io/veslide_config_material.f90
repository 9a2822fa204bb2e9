!> &material: the solid (elastic, the paper's one-term law, creep or relaxation Prony series)
module veslide_config_material
    use veslide_kinds, only: dp
    use veslide_error, only: error_t, fatal_error
    use veslide_strings, only: str
    use veslide_config_common, only: namelist_status, require, choices_text, is_one_of, max_list
    use veslide_material, only: material_model_names
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
    end type material_config_t

    real(dp), parameter :: unset = -huge(1.0_dp)

contains

    !> Read &material from the open namelist file `u` (absent: defaults) and check it
    subroutine read_material_config(self, u, path, error)
        type(material_config_t), intent(out) :: self
        integer, intent(in) :: u
        character(len=*), intent(in) :: path
        type(error_t), allocatable, intent(out) :: error
        character(len=16) :: model
        real(dp) :: young_pa, poisson, einf_pa, ratio, tau_s, e0_pa, big
        real(dp) :: creep_c_per_pa(max_list), creep_tau_s(max_list), relax_e_pa(max_list), relax_rho_s(max_list)
        integer :: stat
        character(len=512) :: msg
        namelist /material/ model, young_pa, poisson, einf_pa, ratio, tau_s, e0_pa, creep_c_per_pa, creep_tau_s, &
            relax_e_pa, relax_rho_s
        model = 'elastic'; young_pa = self%young_pa; poisson = self%poisson; einf_pa = self%einf_pa
        ratio = self%ratio; tau_s = self%tau_s; e0_pa = self%e0_pa
        creep_c_per_pa = unset; creep_tau_s = unset; relax_e_pa = unset; relax_rho_s = unset
        rewind (u); read (u, nml=material, iostat=stat, iomsg=msg)
        call namelist_status(stat, msg, path, 'material', error); if (allocated(error)) return
        self%model = trim(model); self%young_pa = young_pa; self%poisson = poisson; self%einf_pa = einf_pa
        self%ratio = ratio; self%tau_s = tau_s; self%e0_pa = e0_pa
        select case (self%model)
        case ('creep')
            call take_series('creep_c_per_pa', creep_c_per_pa, 'creep_tau_s', creep_tau_s)
        case ('relaxation')
            call take_series('relax_e_pa', relax_e_pa, 'relax_rho_s', relax_rho_s)
        case default
            allocate (self%prony_coef(0), self%prony_time_s(0))
        end select
        if (allocated(error)) return

        big = huge(1.0_dp)
        call require(error, poisson >= 0.0_dp .and. poisson <= 0.5_dp, path, 'material', 'poisson', str(poisson), &
                     "0 to 0.5")
        call require(error, is_one_of(self%model, material_model_names), path, 'material', 'model', &
                     "'"//self%model//"'", choices_text(material_model_names))
        if (allocated(error)) return
        select case (self%model)
        case ('elastic')
            call require(error, young_pa > 0.0_dp .and. young_pa < big, path, 'material', 'young_pa', str(young_pa), &
                         "> 0 [Pa]")
        case ('one_term')
            call require(error, einf_pa > 0.0_dp .and. einf_pa < big, path, 'material', 'einf_pa', str(einf_pa), &
                         "> 0 [Pa]")
            call require(error, ratio > 1.0_dp .and. ratio < big, path, 'material', 'ratio', str(ratio), "> 1 (Einf/E0)")
            call require(error, tau_s > 0.0_dp .and. tau_s < big, path, 'material', 'tau_s', str(tau_s), "> 0 [s]")
        case ('creep', 'relaxation')
            call require(error, e0_pa > 0.0_dp .and. e0_pa < big, path, 'material', 'e0_pa', str(e0_pa), "> 0 [Pa]")
            call require(error, all(self%prony_coef > 0.0_dp) .and. all(self%prony_time_s > 0.0_dp), path, &
                         'material', 'Prony terms', "", "every coefficient and time > 0")
            if (self%model == 'creep') &
                call require(error, sum(self%prony_coef) < 1.0_dp/e0_pa, path, 'material', 'creep_c_per_pa', &
                             "sum "//str(sum(self%prony_coef)), &
                             "sum below 1/e0_pa = "//str(1.0_dp/e0_pa)//" (so that Einf > E0)")
        end select

    contains

        subroutine take_series(name_c, c, name_t, t)
            character(len=*), intent(in) :: name_c, name_t
            real(dp), intent(in) :: c(:), t(:)
            integer :: nc, nt
            nc = count(c /= unset); nt = count(t /= unset)
            if (nc == 0 .or. nc /= nt .or. any(c(1:nc) == unset) .or. any(t(1:nt) == unset)) then
                call fatal_error(error, "veslide: "//path//": &material: "//name_c//" and "//name_t// &
                    " must list the same number (1 to 64) of terms, without gaps"); return
            end if
            self%prony_coef = c(1:nc); self%prony_time_s = t(1:nt)
        end subroutine take_series

    end subroutine read_material_config

end module veslide_config_material
